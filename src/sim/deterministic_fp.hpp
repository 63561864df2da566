#pragma once
// Included first by every simulator source whose floating-point results must be identical on
// every platform: it forbids contracting a*b+c into a fused multiply-add, which GCC does by
// default whenever the target has FMA (-march=native, aarch64) and which rounds differently.
// The rest of IEEE-754 arithmetic (+ - * / sqrt, round-to-nearest) is already deterministic.
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif
