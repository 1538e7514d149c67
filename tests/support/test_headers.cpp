// The translation unit that carries the test executables' precompiled
// headers (sp_test_headers in tests/CMakeLists.txt); it holds no code.
