// tessera morph: the image morph (docs/INTERPOLATION.md). Two images, two 2D meshes of one
// connectivity in pixel coordinates (holes allowed), tags with interpolating
// vertices; K frames of the image morph (core/morph/image_morph.h).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "client/cli/commands.h"
#include "core/io/mesh_import.h"
#include "core/io/png_image.h"
#include "core/io/tag_file.h"
#include "core/morph/image_morph.h"
#include "core/morph/morph.h"

namespace tessera::cli {

namespace {

struct MorphArgs {
  std::string from, to, meshFrom, meshTo, tags, output, strip;
  int level = 2;
  int frames = 0;
};

struct InterpolatingLine {
  uint32_t vertex;
  double tension;
  int line;
};

// The tag file's own lines (crease, corner) go to parseTags; "interpolate V
// [TENSION]" lines name base vertices that interpolate in both keys.
Expected<std::vector<InterpolatingLine>> splitTags(const std::string& text, const std::string& source,
                                                   std::string& rest) {
  std::vector<InterpolatingLine> out;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    std::istringstream words(line);
    std::string first;
    words >> first;
    if (first != "interpolate") {
      rest += line + "\n";
      continue;
    }
    rest += "\n";  // keeps parseTags' line numbers
    InterpolatingLine tag{0, 1.0, number};
    long long vertex = -1;
    if (!(words >> vertex) || vertex < 0) {
      return parseError(source + ":" + std::to_string(number) + ": expected 'interpolate VERTEX [TENSION]'");
    }
    tag.vertex = static_cast<uint32_t>(vertex);
    if (std::string tension; words >> tension) {
      char* end = nullptr;
      tag.tension = std::strtod(tension.c_str(), &end);
      if (end == tension.c_str() || *end != '\0') {
        return parseError(source + ":" + std::to_string(number) + ": bad tension '" + tension + "'");
      }
    }
    if (std::string extra; words >> extra) {
      return parseError(source + ":" + std::to_string(number) + ": unexpected '" + extra + "'");
    }
    out.push_back(tag);
  }
  return out;
}

Expected<Document> keyDocument(const std::string& path, const std::vector<FeatureTag>& tags,
                               const std::string& tagSource,
                               const std::vector<InterpolatingLine>& interpolating, int level) {
  TESSERA_ASSIGN_OR_RETURN(BaseMesh mesh, importMesh(path));
  if (!tags.empty()) TESSERA_RETURN_IF_ERROR(applyTags(tags, tagSource, mesh));
  TESSERA_ASSIGN_OR_RETURN(Document doc, Document::create(mesh, {.maxLevel = level}));
  for (const InterpolatingLine& t : interpolating) {
    auto made = doc.setInterpolation(VertexId(0, t.vertex), true, t.tension);
    if (!made.isOk())
      return made.status().withContext(tagSource + ":" + std::to_string(t.line) + " (" + path + ")");
  }
  return doc;
}

// Frames side by side, each shrunk by a whole factor so that the strip is at
// most 1600 pixels wide (box filter).
Image strip(const std::vector<Image>& frames) {
  const int n = static_cast<int>(frames.size());
  const int w = frames[0].width, h = frames[0].height;
  int factor = 1;
  while (n * w / factor > 1600 && factor < w) ++factor;
  const int fw = w / factor, fh = h / factor;
  Image out{n * fw, fh, std::vector<uint8_t>(static_cast<size_t>(n) * fw * fh * 4)};
  for (int k = 0; k < n; ++k) {
    for (int y = 0; y < fh; ++y) {
      for (int x = 0; x < fw; ++x) {
        for (int c = 0; c < 4; ++c) {
          int sum = 0;
          for (int dy = 0; dy < factor; ++dy) {
            for (int dx = 0; dx < factor; ++dx) sum += frames[k].at(x * factor + dx, y * factor + dy)[c];
          }
          out.at(k * fw + x, y)[c] = static_cast<uint8_t>(sum / (factor * factor));
        }
      }
    }
  }
  return out;
}

int runMorph(const MorphArgs& args) {
  const char* kName = "morph";
  if (args.frames < 1) return usage(kName, "--frames: at least 1");
  if (args.level < 1 || args.level > 6)
    return usage(kName, "--level: 1 to 6 (interpolating vertices need a finer level)");
  auto a = readPng(args.from);
  if (!a.isOk()) return fail(kName, a.status());
  auto b = readPng(args.to);
  if (!b.isOk()) return fail(kName, b.status());
  std::vector<FeatureTag> tags;
  std::vector<InterpolatingLine> interpolating;
  if (!args.tags.empty()) {
    std::ifstream in(args.tags);
    if (!in) return fail(kName, args.tags + ": cannot read");
    std::stringstream text;
    text << in.rdbuf();
    std::string rest;
    auto split = splitTags(text.str(), args.tags, rest);
    if (!split.isOk()) return fail(kName, split.status());
    interpolating = std::move(*split);
    auto parsed = parseTags(rest, args.tags);
    if (!parsed.isOk()) return fail(kName, parsed.status());
    tags = std::move(*parsed);
  }
  auto key0 = keyDocument(args.meshFrom, tags, args.tags, interpolating, args.level);
  if (!key0.isOk()) return fail(kName, key0.status());
  auto key1 = keyDocument(args.meshTo, tags, args.tags, interpolating, args.level);
  if (!key1.isOk()) return fail(kName, key1.status());
  if (Status same =
          checkSameConnectivity(key0->baseTopology(), key1->baseTopology(), args.meshFrom, args.meshTo);
      !same.isOk()) {
    return fail(kName, same);
  }
  auto morph = Morph::create({std::move(*key0), std::move(*key1)});
  if (!morph.isOk()) return fail(kName, morph.status());
  auto mesh0 = planarLimitMesh(morph->key(0), args.level);
  auto mesh1 = planarLimitMesh(morph->key(1), args.level);
  if (!mesh0.isOk() || !mesh1.isOk()) return fail(kName, mesh0.isOk() ? mesh1.status() : mesh0.status());
  std::error_code ec;
  std::filesystem::create_directories(args.output, ec);
  if (ec) return fail(kName, args.output + ": " + ec.message());
  std::vector<Image> frames;
  for (int k = 0; k < args.frames; ++k) {
    const double t = args.frames == 1 ? 0.0 : static_cast<double>(k) / (args.frames - 1);
    auto doc = morph->at(t);
    if (!doc.isOk()) return fail(kName, doc.status());
    auto mesh = planarLimitMesh(*doc, args.level);
    if (!mesh.isOk()) return fail(kName, mesh.status());
    // The paper's named failure (core/morph/image_morph.h): drawn anyway, a folded mesh shows image
    // parts twice and others not at all.
    const Folds folds = foldsBetween(*mesh0, *mesh);
    if (folds.count > 0) {
      char where[64];
      std::snprintf(where, sizeof where, "%.4g", t);
      return fail(kName, "frame " + std::to_string(k) + " (t = " + where + "): " +
                             std::to_string(folds.count) + " of " + std::to_string(mesh->triangles.size()) +
                             " triangles of the level-" + std::to_string(args.level) +
                             " surface fold over (the first is triangle " + std::to_string(folds.first) +
                             "); the meshes do not give a valid warp. Move the vertices of " + args.meshTo +
                             " so that no triangle turns over on the way");
    }
    Image frame = morphFrame(*a, *b, *mesh0, *mesh1, *mesh, t);
    char name[32];
    std::snprintf(name, sizeof name, "/frame_%04d.png", k);
    if (Status w = writePng(args.output + name, frame); !w.isOk()) return fail(kName, w);
    if (!args.strip.empty()) frames.push_back(std::move(frame));
  }
  if (!args.strip.empty()) {
    if (Status w = writePng(args.strip, strip(frames)); !w.isOk()) return fail(kName, w);
  }
  std::printf("wrote %d frames to %s (%d x %d pixels, level %d, %zu triangles, %zu interpolating vertices)\n",
              args.frames, args.output.c_str(), a->width, a->height, args.level, mesh0->triangles.size(),
              interpolating.size());
  return 0;
}

}  // namespace

void addMorphCommand(CLI::App& app, Action& action) {
  CLI::App* sub = app.add_subcommand(
      "morph", "morph two images through two 2D meshes (docs/INTERPOLATION.md, \"The image morph\")");
  sub->footer(
      "Meshes: OBJ/OFF/PLY... in pixel coordinates of their image (x right, y down), one connectivity, holes "
      "allowed.\nTags: crease/corner lines as in --tags elsewhere, and 'interpolate VERTEX [TENSION]' for "
      "base "
      "vertices the surface passes through in both keys.\nFrames: DIR/frame_0000.png ...; outside the shape "
      "the two "
      "images are cross-dissolved as they are.");
  auto args = std::make_shared<MorphArgs>();
  sub->add_option("--from", args->from, "the first image (PNG)")->required()->type_name("A.png");
  sub->add_option("--to", args->to, "the second image (PNG)")->required()->type_name("B.png");
  sub->add_option("--mesh-from", args->meshFrom, "the mesh over the first image")
      ->required()
      ->type_name("MA");
  sub->add_option("--mesh-to", args->meshTo, "the same mesh moved over the second image")
      ->required()
      ->type_name("MB");
  sub->add_option("--tags", args->tags, "creases, corners and interpolating vertices of both meshes")
      ->type_name("FILE");
  sub->add_option("--level", args->level, "subdivision level of the warp (default 2)")->check(wholeNumber());
  sub->add_option("--frames", args->frames, "how many frames, t from 0 to 1")
      ->required()
      ->check(wholeNumber());
  sub->add_option("-o,--output", args->output, "the directory for the frames")->required()->type_name("DIR");
  sub->add_option("--strip", args->strip, "also write every frame side by side into one PNG")
      ->type_name("FILE");
  onChosen(*sub, action, [args] { return runMorph(*args); });
}

}  // namespace tessera::cli
