// The positive control of the contraction test: the same expression as raykernel::detail::contraction_probe,
// deliberately compiled with -ffp-contract=fast -mfma (tests/CMakeLists.txt), so that the test can show it
// detects a contracting build.
namespace raykernel::test_support {
double contracting_probe(double a, double c) noexcept { return a * a - c; }
}  // namespace raykernel::test_support
