#pragma once
// Time inside the stack: seconds as double on the clock of the run (real, simulated or lockstep).
// double keeps ~0.1 µs resolution over days, enough for every sensor here, and keeps algorithm code plain.
namespace fsd {
using Stamp = double;     // seconds since the clock's epoch
using Duration = double;  // seconds
}  // namespace fsd
