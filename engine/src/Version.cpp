#include <preskin/Version.h>

namespace preskin {

const char* version() { return PRESKIN_VERSION_STRING; }

}  // namespace preskin
