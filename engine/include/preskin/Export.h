// Symbol visibility for libpreskin. The library is built with hidden visibility so that its
// internal Vulkan loader (volk) never clashes with a host that links the Vulkan loader itself;
// only declarations marked PRESKIN_API are exported.
#pragma once

#if defined(PRESKIN_STATIC)
#define PRESKIN_API
#elif defined(PRESKIN_BUILDING_LIBRARY)
#define PRESKIN_API __attribute__((visibility("default")))
#else
#define PRESKIN_API
#endif
