#include "client/replay/proc_sample.h"

#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace tessera::replay {

ProcSample sampleProcess(int pid) {
  ProcSample p;
  if (pid <= 0) return p;
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string text;
  if (!std::getline(stat, text)) return p;
  // Fields after the command name (which may hold spaces) start at field 3.
  const size_t paren = text.rfind(')');
  if (paren == std::string::npos || paren + 2 > text.size()) return p;
  std::istringstream in(text.substr(paren + 2));
  std::vector<std::string> fields;
  for (std::string f; in >> f;) fields.push_back(f);
  if (fields.size() < 13) return p;
  const double ticks = static_cast<double>(sysconf(_SC_CLK_TCK));
  p.cpuSeconds = (std::stod(fields[11]) + std::stod(fields[12])) / ticks;  // utime, stime (fields 14, 15)
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmRSS:", 0) == 0) p.rssBytes = std::stoll(line.substr(6)) * 1024;
  }
  p.ok = true;
  return p;
}

}  // namespace tessera::replay
