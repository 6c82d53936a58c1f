// Forbids fused multiply-adds in the translation unit that includes it (after its standard
// headers): seeded synthetic records must come out bit-identical from every build, and a
// compiler free to contract a * b + c (GCC by default in C++, clang when the target has
// FMA, every aarch64 build) rounds differently. Internal.
#pragma once

#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif
