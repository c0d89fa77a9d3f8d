#pragma once
// The one exception type of the core: input that cannot be used. The CLI turns it into exit code 2, the wasm
// bindings into an error string, so its message must name the problem and the first offending element.
#include <stdexcept>

namespace tvf {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace tvf
