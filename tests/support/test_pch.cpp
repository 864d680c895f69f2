// Anchor of the tests' precompiled header (tests/support/test_pch.h): CMake builds the header
// with this target's flags, and every test executable reuses it.
