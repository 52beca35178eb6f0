// tessera doc view (doc_view.cc): what a view of a document would be sent
// (docs/VIEWS.md): its tiles by level, their triangles, bytes and errors.
#pragma once

#include <array>
#include <string>

namespace tessera::cli {

struct DocViewArgs {
  std::string document;
  std::array<double, 3> eye{0, 0, 0}, target{0, 0, 0}, up{0, 1, 0};
  double fovDegrees = 50;
  double orthoHeight = 0;  // > 0: orthographic
  std::string size = "390x844";
  double tolerance = 1;
  long long budget = 0;
};

int runDocView(const DocViewArgs& args);

}  // namespace tessera::cli
