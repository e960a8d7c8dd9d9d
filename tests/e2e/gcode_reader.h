// A small G-code reader for the end-to-end tests: moves with their layer, type and E, in the
// dialect tranche writes (G0/G1, G92, M82/M83, ;LAYER:, ;TYPE:, ;Z:).
#pragma once

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace tranche::test {

struct Move {
  double x0, y0, x, y;  // from, to (mm, bed coordinates)
  double e;             // E word as written (absolute or relative)
  double de;            // E advance of this move (mm of filament)
  bool has_e, has_xy;
  std::string type;  // ;TYPE: in force
  int layer;
  double f = 0;       // feed rate in force (mm/min)
  double fan = 0;     // part fan in force (0..1)
  size_t line = 0;    // index in Gcode::lines
};

struct Gcode {
  std::string text;
  std::vector<Move> moves;
  std::map<int, double> layer_z;  // ;LAYER:n -> ;Z:
  int layer_count_header = -1;
  bool relative_e = false;
  int g92_resets = 0;
  std::vector<std::string> lines;

  bool contains(const std::string& s) const { return text.find(s) != std::string::npos; }
  double filament() const {
    double f = 0;
    for (const auto& m : moves)
      if (m.has_xy && m.de > 0) f += m.de;
    return f;
  }
};

inline double word(const std::string& line, char w, bool& found) {
  for (size_t i = 0; i < line.size(); ++i) {
    if (line[i] == ';') break;
    if (line[i] == w && (i == 0 || line[i - 1] == ' ')) {
      found = true;
      return std::stod(line.substr(i + 1));
    }
  }
  found = false;
  return 0;
}

inline Gcode read_gcode(const std::string& path) {
  Gcode g;
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  g.text = ss.str();
  std::istringstream lines(g.text);
  std::string line, type;
  int layer = -1;
  double x = 0, y = 0, e = 0, z = 0, feed = 0, fan = 0;
  while (std::getline(lines, line)) {
    g.lines.push_back(line);
    if (line.rfind("M107", 0) == 0) fan = 0;
    if (line.rfind("M106", 0) == 0) {
      bool found;
      double s = word(line, 'S', found);
      fan = !found ? 1.0 : line.find(" P") != std::string::npos ? s : s / 255.0;  // RepRapFirmware: P0 S0..1
    }
    if (line.rfind(";LAYER:", 0) == 0) {
      layer = std::stoi(line.substr(7));
      g.layer_z[layer] = z;
      continue;
    }
    if (line.rfind(";Z:", 0) == 0) z = std::stod(line.substr(3));
    if (line.rfind(";LAYER_COUNT:", 0) == 0) g.layer_count_header = std::stoi(line.substr(13));
    if (line.rfind(";TYPE:", 0) == 0) type = line.substr(6);
    if (line.rfind("M83", 0) == 0) g.relative_e = true;
    if (line.rfind("M82", 0) == 0) g.relative_e = false;
    if (line.rfind("G92", 0) == 0) {
      bool f;
      double v = word(line, 'E', f);
      if (f) e = v, ++g.g92_resets;
      continue;
    }
    if (line.rfind("G1 ", 0) == 0 || line.rfind("G0 ", 0) == 0) {
      bool fx, fy, fe;
      double nx = word(line, 'X', fx), ny = word(line, 'Y', fy), ev = word(line, 'E', fe);
      bool ff;
      double nf = word(line, 'F', ff);
      if (ff) feed = nf;
      Move m{x, y, fx ? nx : x, fy ? ny : y, ev, 0, fe, fx || fy, type, layer, feed, fan, g.lines.size() - 1};
      if (fe) {
        double ne = g.relative_e ? e + ev : ev;
        m.de = ne - e;
        e = ne;
      }
      x = m.x;
      y = m.y;
      g.moves.push_back(m);
    }
  }
  return g;
}

}  // namespace tranche::test
