#include "client/view/view_options.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <charconv>
#include <fstream>
#include <memory>

#include "tessera/version.h"

namespace tessera::view {

namespace {

// Options whose text is split after parsing (HOST:PORT, WxH, DX,DY, a file).
struct RawOptions {
  std::string connect, size, drag, tokenFile;
  std::string codec = "draco";
  bool profile = false;
};

template <typename T>
Status parseNumber(const std::string& option, const std::string& text, T lo, T hi, T* out) {
  T value{};
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || value < lo || value > hi) {
    return invalidArgument(option + ": expected a number in [" + std::to_string(lo) + ", " +
                           std::to_string(hi) + "], got '" + text + "'");
  }
  *out = value;
  return Status::ok();
}

// "A<sep>B" as two numbers in [lo, hi]; `what` names the option and the form.
Status parsePair(const std::string& option, const std::string& form, const std::string& text, char sep,
                 int lo, int hi, int* a, int* b) {
  const size_t at = text.find(sep);
  if (at == std::string::npos) return invalidArgument(option + " expects " + form + ", got '" + text + "'");
  TESSERA_RETURN_IF_ERROR(parseNumber<int>(option, text.substr(0, at), lo, hi, a));
  return parseNumber<int>(option, text.substr(at + 1), lo, hi, b);
}

// A range check whose bounds the option's description gives in words.
template <typename T>
CLI::Validator within(T lo, T hi) {
  return CLI::Range(lo, hi).description("");
}

std::unique_ptr<CLI::App> makeApp(ViewOptions& o, RawOptions& raw, bool& noHud, bool& noGizmo) {
  auto app = std::make_unique<CLI::App>(
      "tessera-view: shows and edits one document of a tessera-server (docs/VIEWER.md)", "tessera-view");
  app->set_version_flag("--version", std::string("tessera-view ") + kVersion);
  app->get_formatter()->column_width(26);

  const std::string connection = "Connection", display = "Display", headless = "Headless";
  app->add_option("--connect", raw.connect, "the server (required)")
      ->type_name("HOST:PORT")
      ->group(connection);
  app->add_option("--token", o.token, "access token: the viewer role watches, the editor role edits")
      ->type_name("T")
      ->group(connection);
  app->add_option("--token-file", raw.tokenFile, "read the token from the first line of FILE")
      ->type_name("FILE")
      ->group(connection);
  app->add_option("--document", o.document, "document id (required)")
      ->type_name("D")
      ->check(within(uint64_t{1}, UINT64_MAX))
      ->group(connection);
  app->add_option("--name", o.name, "shown to collaborators (default tessera-view)")
      ->type_name("NAME")
      ->group(connection);
  auto* views = app->add_flag("--views", o.views,
                              "the default: tiles chosen for the camera by screen-space error, sent again "
                              "as it moves (docs/VIEWER.md \"Views\")")
                    ->group(connection);
  auto* profile =
      app->add_flag("--profile", raw.profile,
                    "subscribe with the LOD profile instead of a view (implied by --base-level, --max-level, "
                    "--angle and the --morph options)")
          ->excludes(views)
          ->group(connection);
  app->add_option("--tolerance", o.tolerancePixels, "views: the screen-space error in pixels (default 1)")
      ->type_name("PX")
      ->check(CLI::Range(0.25, 256.0))
      ->excludes(profile)
      ->group(connection);
  app->add_option("--base-level", o.baseLevel, "LOD profile: minimum level, 0 to 20 (default 1)")
      ->type_name("N")
      ->check(within(0u, 20u))
      ->group(connection);
  app->add_option("--max-level", o.maxLevel, "LOD profile: maximum level, 0 to 20 (default 3)")
      ->type_name("N")
      ->check(within(0u, 20u))
      ->group(connection);
  app->add_option("--angle", o.angle, "LOD profile: refine where normals differ more (default 15)")
      ->type_name("DEGREES")
      ->check(within(0.0, 180.0))
      ->group(connection);
  app->add_option("--morph-t", o.morphT,
                  "a morph document: show it at time T in [0, 1] (0 key 0, 1 key 1; keys , . and P)")
      ->type_name("T")
      ->check(within(0.0, 1.0))
      ->group(connection);
  app->add_option("--morph-rate", o.morphRate,
                  "a morph document: P plays it at this many t per second (default 0.25)")
      ->type_name("RATE")
      ->check(within(0.001, 100.0))
      ->group(connection);
  app->add_flag("--morph-coarse", o.morphCoarse,
                "a morph document: show every time from its control points refined here, paused too "
                "(by default only playing does; paused shows the server's exact surface)")
      ->group(connection);
  app->add_option("--codec", raw.codec,
                  "region codec, draco (the default) or meshopt; meshopt needs a profile subscription, "
                  "views come in Draco only (docs/REGION_ENCODING.md \"meshopt regions\")")
      ->type_name("CODEC")
      ->check(CLI::IsMember({"draco", "meshopt"}))
      ->group(connection);
  app->add_option("--timeout", o.timeoutSeconds, "to connect and get the first snapshot (default 30)")
      ->type_name("SECONDS")
      ->check(within(0.1, 3600.0))
      ->group(connection);

  app->add_option("--size", raw.size, "window or screenshot size (default 800x600)")
      ->type_name("WxH")
      ->group(display);
  app->add_option("--msaa", o.msaa, "multisample anti-aliasing: samples per pixel, 0 for none (default 4)")
      ->type_name("N")
      ->check(within(0, 16))
      ->group(display);
  app->add_flag("--matcap", o.matcap, "matcap shading instead of key, fill and sky light (key M)")
      ->group(display);
  app->add_flag("--wireframe", o.wireframe, "wireframe overlay (key W)")->group(display);
  app->add_flag("--level-colours,--level-colors", o.levelColours, "views: tiles coloured by level (key L)")
      ->group(display);
  app->add_flag("--region-colours,--region-colors", o.regionColours, "one colour per region (key C)")
      ->group(display);
  app->add_flag("--control-points", o.controlPoints, "show the control vertices (key V; off by default)")
      ->group(display);
  app->add_flag("--cage", o.cage,
                "draw the control cage of --level as polygons between its control vertices (key O)")
      ->group(display);
  app->add_option("--level", o.controlLevel, "level whose control vertices are shown and dragged (default 0)")
      ->type_name("N")
      ->check(within(0, 20))
      ->group(display);
  app->add_flag("--no-hud", noHud, "no HUD")->group(display);
  app->add_flag("--hud-collapsed", o.hudCollapsed, "start with the HUD collapsed to its title line (key H)")
      ->group(display);
  app->add_flag("--no-gizmo", noGizmo, "no axes gizmo (key G)")->group(display);
  app->add_option("--refine", o.refine,
                  "client-side refinement: split each edge up to N times, 0 to 2 (default 0; key R cycles)")
      ->type_name("N")
      ->check(within(0, 2))
      ->group(display);

  app->add_option("--screenshot", o.screenshot,
                  "render without any display (EGL), --frames frames after the first snapshot, write "
                  "this PNG and exit")
      ->type_name("OUT.png")
      ->group(headless);
  app->add_option("--frames", o.frames, "frames to render before the screenshot (default 30)")
      ->type_name("N")
      ->check(within(1, 100000))
      ->group(headless);
  app->add_option("--drag", raw.drag,
                  "self-test: first drag the control vertex nearest the centre by DX,DY pixels "
                  "(write a negative DX as --drag=-80,80)")
      ->type_name("DX,DY")
      ->group(headless);
  app->add_flag("--edit-keys", o.editKeys,
                "self-test: first pick an edge and press E, 2, K, Ctrl+Z three times and Ctrl+Y, "
                "printing the surface hash after each")
      ->group(headless);
  app->add_flag("--surface-hash", o.hashSurfaces,
                "print the surface hash (docs/PROTOCOL.md 6.5) of the regions received at the end, "
                "the same for either codec")
      ->group(headless);
  return app;
}

// CLI11 says "--frames: Value x not in range ..."; ours add no prefix.
Status usageError(const CLI::Error& e) {
  return invalidArgument(e.what());
}

}  // namespace

Status checkCodec(const ViewOptions& options) {
  if (options.codec != RegionCodec::kMeshopt || !options.views) return Status::ok();
  return invalidArgument(
      "--codec meshopt: the server sends a view-dependent subscription (--views, the default) in "
      "Draco only (docs/REGION_ENCODING.md \"meshopt regions\"); pass --profile (or --base-level, "
      "--max-level, --angle) to receive meshopt regions, or leave out --codec for a view");
}

std::string viewHelp() {
  ViewOptions o;
  RawOptions raw;
  bool noHud = false, noGizmo = false;
  return makeApp(o, raw, noHud, noGizmo)->help();
}

Expected<ViewOptions> parseViewOptions(const std::vector<std::string>& args) {
  ViewOptions o;
  RawOptions raw;
  bool noHud = false, noGizmo = false;
  auto app = makeApp(o, raw, noHud, noGizmo);
  try {
    std::vector<std::string> reversed(args.rbegin(), args.rend());
    app->parse(reversed);
  } catch (const CLI::CallForHelp&) {
    o.help = true;
    return o;
  } catch (const CLI::CallForVersion&) {
    o.version = true;
    return o;
  } catch (const CLI::ParseError& e) {
    return usageError(e);
  }
  o.hud = !noHud;
  o.gizmo = !noGizmo;
  // A view is the default (docs/VIEWER.md "Views"); naming any of the
  // profile's fields asks for the profile, as --profile does.
  const bool profileNamed = raw.profile || app->count("--base-level") || app->count("--max-level") ||
                            app->count("--angle") || app->count("--morph-t") ||
                            app->count("--morph-coarse") || app->count("--morph-rate");
  if (o.views && profileNamed)
    return invalidArgument(
        "--views: the LOD profile options (--base-level, --max-level, --angle, --morph-*) "
        "choose a profile; give one or the other");
  o.views = !profileNamed;
  o.codec = raw.codec == "meshopt" ? RegionCodec::kMeshopt : RegionCodec::kDraco;
  TESSERA_RETURN_IF_ERROR(checkCodec(o));
  if (raw.connect.empty()) return invalidArgument("--connect HOST:PORT is required");
  const size_t colon = raw.connect.rfind(':');
  if (colon == std::string::npos || colon == 0)
    return invalidArgument("--connect expects HOST:PORT, got '" + raw.connect + "'");
  o.host = raw.connect.substr(0, colon);
  TESSERA_RETURN_IF_ERROR(
      parseNumber<uint16_t>("--connect port", raw.connect.substr(colon + 1), 1, 65535, &o.port));
  if (!raw.tokenFile.empty()) {
    std::ifstream in(raw.tokenFile);
    if (!in) return invalidArgument("--token-file " + raw.tokenFile + ": cannot open the file");
    std::getline(in, o.token);
    if (o.token.empty()) return invalidArgument("--token-file " + raw.tokenFile + ": no token in the file");
  }
  if (!raw.size.empty())
    TESSERA_RETURN_IF_ERROR(parsePair("--size", "WxH", raw.size, 'x', 64, 8192, &o.width, &o.height));
  if (!raw.drag.empty()) {
    TESSERA_RETURN_IF_ERROR(parsePair("--drag", "DX,DY", raw.drag, ',', -8192, 8192, &o.dragX, &o.dragY));
    o.drag = true;
  }
  if (o.editKeys) o.hashSurfaces = true;
  if (o.document == 0) return invalidArgument("--document D is required");
  if (o.drag && o.screenshot.empty()) return invalidArgument("--drag needs --screenshot");
  if (o.editKeys && o.screenshot.empty()) return invalidArgument("--edit-keys needs --screenshot");
  if (o.editKeys && o.drag) return invalidArgument("--edit-keys and --drag are separate self-tests");
  if (o.hashSurfaces && o.screenshot.empty()) return invalidArgument("--surface-hash needs --screenshot");
  if (o.baseLevel > o.maxLevel) return invalidArgument("--base-level must not exceed --max-level");
  // The self-tests pick control vertices, which needs them shown.
  if (o.drag || o.editKeys) o.controlPoints = true;
  return o;
}

}  // namespace tessera::view
