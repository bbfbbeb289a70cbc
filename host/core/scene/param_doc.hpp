// The parameter reference docs/parameters.md, generated from the parameter table.
#pragma once

#include <string>

namespace clothsim {

// The whole of docs/parameters.md (tools/params_doc writes and checks the committed file).
std::string parameters_markdown();

}  // namespace clothsim
