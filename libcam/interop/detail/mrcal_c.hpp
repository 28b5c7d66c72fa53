#pragma once
// mrcal's C headers, wrapped: they declare C functions without extern "C" guards.
// Include mrcal only through this header. (The include directory is a SYSTEM one, so
// the C idioms in those headers raise no C++ warnings.)

extern "C" {
#include <mrcal/mrcal.h>
}
