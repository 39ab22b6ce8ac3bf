// The owner of the test programs' precompiled headers (tests/CMakeLists.txt,
// rgraph_test_pch): every suite reuses the headers this target compiles. It
// has no tests of its own; it exists because a PCH is only valid for sources
// compiled with the same flags, and test programs are executables (-fPIE).
int main() { return 0; }
