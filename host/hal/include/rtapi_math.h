/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * rtapi_math.h - the C maths library for components (sin, cos, fabs, sqrt,
 * floor, ...; link with -lm, which halcompile does), plus the constants
 * LinuxCNC components rely on being there.
 */
#ifndef HM_RTAPI_MATH_H
#define HM_RTAPI_MATH_H

#include <float.h>
#include <math.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif
#ifndef M_PI_2
#define M_PI_2 1.57079632679489661923
#endif
#ifndef M_PI_4
#define M_PI_4 0.78539816339744830962
#endif
#ifndef M_E
#define M_E 2.7182818284590452354
#endif
#ifndef M_SQRT2
#define M_SQRT2 1.41421356237309504880
#endif
#ifndef M_SQRT1_2
#define M_SQRT1_2 0.70710678118654752440
#endif
#ifndef M_LN2
#define M_LN2 0.69314718055994530942
#endif
#ifndef M_LN10
#define M_LN10 2.30258509299404568402
#endif
#ifndef M_1_PI
#define M_1_PI 0.31830988618379067154
#endif
#ifndef M_2_PI
#define M_2_PI 0.63661977236758134308
#endif

#endif /* HM_RTAPI_MATH_H */
