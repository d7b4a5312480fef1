#pragma once
// The project's statuses as Python exceptions: imagepro.Error, and under it one class
// per failure status with the status's name (imagepro.NoTarget, imagepro.FileNotFound, ...).
// C++ code throws StatusError; the translator registered by bindErrors raises the class.
#include <stdexcept>
#include <string>

#include "core/common/status.h"

namespace imagepro::python {

class StatusError : public std::runtime_error {
 public:
  // `detail` says what went wrong where; empty: the status's own sentence.
  StatusError(Status status, const std::string& detail);
  Status status() const { return status_; }

 private:
  Status status_;
};

}  // namespace imagepro::python
