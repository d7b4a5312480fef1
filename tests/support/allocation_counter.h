#pragma once
// Counts every global operator new of the test program that links
// tests/support/allocation_counter.cpp (it replaces operator new and delete, so it
// goes in one executable's sources once). Unlike src/cli/allocation_counter.h it
// sees operator new only, not malloc underneath.
#include <functional>

namespace imagepro::test {

// Calls of operator new since the program started.
long allocationCount();

// The operator new calls made while `work` runs.
long allocationsOf(const std::function<void()>& work);

}  // namespace imagepro::test
