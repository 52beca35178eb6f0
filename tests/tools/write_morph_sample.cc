// Writes the procedural image-morph sample (support/morph_sample.h) into a
// directory: deploy/samples/make_morph_sample.sh runs it.
#include <cstdio>

#include "support/morph_sample.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: write_morph_sample DIR\n");
    return 2;
  }
  const tessera::Status written =
      tessera::testing::writeMorphSample(tessera::testing::makeMorphSample(), argv[1]);
  if (!written.isOk()) {
    std::fprintf(stderr, "write_morph_sample: %s\n", written.message().c_str());
    return 1;
  }
  std::printf("wrote the morph sample to %s\n", argv[1]);
  return 0;
}
