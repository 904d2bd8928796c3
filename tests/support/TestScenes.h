// Scenes built in code for tests: analytic shapes with exact normals and tangents.
#pragma once

#include <preskin/Scene.h>

namespace preskin::test {

// UV sphere of the given radius at the origin (segments around, rings pole to pole).
Primitive makeSphere(float radiusM, uint32_t segments, uint32_t rings);
// A torus about the y axis: the tube of radius minorM around the circle of radius majorM.
Primitive makeTorus(float majorM, float minorM, uint32_t segments, uint32_t rings);
// An open tube along the x axis, centred at the origin, lengthM long (around: quads about the
// axis, along: quads along it), normals outwards.
Primitive makeCylinder(float radiusM, float lengthM, uint32_t around, uint32_t along);
// Square in the XY plane facing +Z, centred at the origin, subdivided n x n.
Primitive makeQuad(float sizeM, uint32_t n);
// Axis-aligned box centred at the origin with outward faces.
Primitive makeBox(const glm::vec3& sizeM);
// A dielectric skin material (default SkinMaterial) of the given albedo and scatter scale.
Material skinMaterial(const glm::vec3& albedo, float scatterScale = 1.0f);
// A scene holding each primitive as one mesh instance with its own transform.
Scene makeScene(const std::vector<std::pair<Primitive, glm::mat4>>& parts, const std::vector<Material>& materials);

}  // namespace preskin::test
