// A whole file as bytes, with errors naming the path and the reason.
#pragma once

#include <string>

#include "core/util/status.h"

namespace tessera {

Expected<std::string> readFile(const std::string& path);

}  // namespace tessera
