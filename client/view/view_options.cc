#include "client/view/view_options.h"

#include <charconv>
#include <fstream>

namespace tessera::view {

const char* const kViewHelp =
    "usage: tessera-view --connect HOST:PORT (--token T | --token-file F) --document D [options]\n"
    "\n"
    "  --name NAME            shown to collaborators (default tessera-view)\n"
    "  --base-level N         LOD profile: minimum level (default 1)\n"
    "  --max-level N          LOD profile: maximum level (default 3)\n"
    "  --angle DEGREES        LOD profile: refine where normals differ more (default 15)\n"
    "  --level N              level whose control vertices are shown and dragged (default 0)\n"
    "  --size WxH             window size (default 800x600)\n"
    "  --wireframe            start with the wireframe overlay on\n"
    "  --region-colours       start with one colour per region\n"
    "  --no-hud               hide the HUD\n"
    "  --refine N             refine the received surface on the client, splitting each\n"
    "                         edge up to N times (0, 1 or 2; default 0; key R cycles)\n"
    "  --screenshot OUT.png   headless: render --frames N frames (default 30) after the\n"
    "                         first snapshot, write OUT.png and exit\n"
    "  --drag DX,DY           headless: first drag the control vertex nearest the centre\n"
    "                         by DX,DY pixels (a self-test of picking and editing)\n"
    "  --edit-keys            headless: first pick an edge and press E, 2, K, Ctrl+Z three\n"
    "                         times, Ctrl+Y, printing the surface hash after each (a self-test)\n"
    "  --timeout SECONDS      to connect and get the first snapshot (default 30)\n";

namespace {

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

}  // namespace

Expected<ViewOptions> parseViewOptions(const std::vector<std::string>& args) {
  ViewOptions o;
  bool haveConnect = false;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--help" || a == "-h") {
      o.help = true;
      return o;
    }
    if (a == "--wireframe") {
      o.wireframe = true;
      continue;
    }
    if (a == "--region-colours" || a == "--region-colors") {
      o.regionColours = true;
      continue;
    }
    if (a == "--no-hud") {
      o.hud = false;
      continue;
    }
    if (a == "--edit-keys") {
      o.editKeys = o.hashSurfaces = true;
      continue;
    }
    if (i + 1 >= args.size()) return invalidArgument(a + ": unknown option or missing value");
    const std::string& v = args[++i];
    if (a == "--connect") {
      const size_t colon = v.rfind(':');
      if (colon == std::string::npos || colon == 0)
        return invalidArgument("--connect expects HOST:PORT, got '" + v + "'");
      o.host = v.substr(0, colon);
      TESSERA_RETURN_IF_ERROR(
          parseNumber<uint16_t>("--connect port", v.substr(colon + 1), 1, 65535, &o.port));
      haveConnect = true;
    } else if (a == "--token") {
      o.token = v;
    } else if (a == "--token-file") {
      std::ifstream in(v);
      std::getline(in, o.token);
      if (o.token.empty()) return invalidArgument("--token-file " + v + ": no token in the file");
    } else if (a == "--name") {
      o.name = v;
    } else if (a == "--document") {
      TESSERA_RETURN_IF_ERROR(parseNumber<uint64_t>(a, v, 1, UINT64_MAX, &o.document));
    } else if (a == "--base-level") {
      TESSERA_RETURN_IF_ERROR(parseNumber<uint32_t>(a, v, 0, 20, &o.baseLevel));
    } else if (a == "--max-level") {
      TESSERA_RETURN_IF_ERROR(parseNumber<uint32_t>(a, v, 0, 20, &o.maxLevel));
    } else if (a == "--angle") {
      TESSERA_RETURN_IF_ERROR(parseNumber<double>(a, v, 0.0, 180.0, &o.angle));
    } else if (a == "--level") {
      TESSERA_RETURN_IF_ERROR(parseNumber<int>(a, v, 0, 20, &o.controlLevel));
    } else if (a == "--refine") {
      TESSERA_RETURN_IF_ERROR(parseNumber<int>(a, v, 0, 2, &o.refine));
    } else if (a == "--size") {
      const size_t x = v.find('x');
      if (x == std::string::npos) return invalidArgument("--size expects WxH, got '" + v + "'");
      TESSERA_RETURN_IF_ERROR(parseNumber<int>("--size width", v.substr(0, x), 64, 8192, &o.width));
      TESSERA_RETURN_IF_ERROR(parseNumber<int>("--size height", v.substr(x + 1), 64, 8192, &o.height));
    } else if (a == "--screenshot") {
      o.screenshot = v;
    } else if (a == "--frames") {
      TESSERA_RETURN_IF_ERROR(parseNumber<int>(a, v, 1, 100000, &o.frames));
    } else if (a == "--drag") {
      const size_t comma = v.find(',');
      if (comma == std::string::npos) return invalidArgument("--drag expects DX,DY, got '" + v + "'");
      TESSERA_RETURN_IF_ERROR(parseNumber<int>("--drag dx", v.substr(0, comma), -8192, 8192, &o.dragX));
      TESSERA_RETURN_IF_ERROR(parseNumber<int>("--drag dy", v.substr(comma + 1), -8192, 8192, &o.dragY));
      o.drag = true;
    } else if (a == "--timeout") {
      TESSERA_RETURN_IF_ERROR(parseNumber<double>(a, v, 0.1, 3600.0, &o.timeoutSeconds));
    } else {
      return invalidArgument("unknown option '" + a + "'");
    }
  }
  if (!haveConnect) return invalidArgument("--connect HOST:PORT is required");
  if (o.document == 0) return invalidArgument("--document D is required");
  if (o.drag && o.screenshot.empty()) return invalidArgument("--drag needs --screenshot");
  if (o.editKeys && o.screenshot.empty()) return invalidArgument("--edit-keys needs --screenshot");
  if (o.editKeys && o.drag) return invalidArgument("--edit-keys and --drag are separate self-tests");
  if (o.baseLevel > o.maxLevel) return invalidArgument("--base-level must not exceed --max-level");
  return o;
}

}  // namespace tessera::view
