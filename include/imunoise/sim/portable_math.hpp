#pragma once
// Elementary functions built from IEEE-754 basic operations (+, -, *, /, sqrt, exact scaling)
// only, so that every platform and compiler produces the same bits. The C library's exp, log
// and sin are allowed to differ in the last place between implementations (glibc, musl, MSVC,
// macOS), which would make simulated samples platform dependent; the simulator uses these
// instead wherever a generated sample depends on an elementary function.
//
// Accuracy (checked in tests/sim/portable_math_test.cpp against long double references on
// 10^5 points per function): exp, expm1 and log within 2 ulp; sin and cos of 2*pi*c within
// 2e-16 absolute. Determinism needs the translation unit compiled without floating-point
// contraction (src/sim sets it), since a fused multiply-add rounds differently.
#include <utility>

namespace imunoise::sim::portable {

/// e^x for finite x; 0 below about -745, +inf above about 709.78.
double exp(double x);

/// e^x - 1 for finite x, accurate also for |x| << 1.
double expm1(double x);

/// Natural logarithm for finite x > 0 (returns NaN for x <= 0 or NaN).
double log(double x);

/// sin(2*pi*c) and cos(2*pi*c) of an angle c given in cycles (turns). The reduction to one
/// turn is exact, so the result stays accurate for large |c| up to 2^52.
std::pair<double, double> sincos_cycles(double cycles);

}  // namespace imunoise::sim::portable
