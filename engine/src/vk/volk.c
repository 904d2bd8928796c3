/* The volk meta-loader, compiled into libpreskin with hidden visibility (see engine/CMakeLists.txt). */
#include <volk.c>
