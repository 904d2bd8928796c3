// The library's version: the project's MAJOR.MINOR.PATCH, as in libpreskin's SONAME and in
// preskin.pc.
#pragma once

#include <preskin/Export.h>

namespace preskin {

// The version of the libpreskin that is loaded (not of the headers a program was compiled with).
PRESKIN_API const char* version();

}  // namespace preskin
