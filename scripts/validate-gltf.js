#!/usr/bin/env node
// Runs the Khronos glTF-Validator (npm package gltf-validator) over the .gltf and .glb files
// given and prints one JSON object per line: {"file", "errors", "warnings", "codes"} (codes of
// the errors and warnings). The module is found as `require('gltf-validator')` would find it,
// or at $PRESKIN_GLTF_VALIDATOR (its folder). Exit status 2 when the module is missing.
'use strict';
const fs = require('fs');
const path = require('path');

let validator;
try {
  validator = require(process.env.PRESKIN_GLTF_VALIDATOR || 'gltf-validator');
} catch (e) {
  console.error('validate-gltf: the gltf-validator module is not installed (npm install gltf-validator)');
  process.exit(2);
}

async function validate(file) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const external = (uri) => new Promise((resolve, reject) => {
    try {
      resolve(new Uint8Array(fs.readFileSync(path.join(path.dirname(file), decodeURIComponent(uri)))));
    } catch (e) {
      reject(e.toString());
    }
  });
  try {
    const report = await validator.validateBytes(bytes, { uri: file, externalResourceFunction: external, maxIssues: 100 });
    const codes = report.issues.messages.filter((m) => m.severity <= 1).map((m) => m.code);
    return { file, errors: report.issues.numErrors, warnings: report.issues.numWarnings, codes };
  } catch (e) {
    return { file, errors: 1, warnings: 0, codes: ['VALIDATOR_EXCEPTION'] };
  }
}

(async () => {
  for (const file of process.argv.slice(2)) console.log(JSON.stringify(await validate(file)));
})();
