#include "solver/scene/parcel_file.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <sstream>
#include <string_view>

#include "solver/scene/table_reader.hpp"

namespace dustlift {
namespace {

/// The columns a layer file may have, in the order PlacedParcel lists them.
enum Column { X, Y, Diameter, Vx, Vy, Omega, Temperature, ParticleDiameter, kColumns };
constexpr std::array<std::string_view, kColumns> kColumnNames{
    "x", "y", "diameter", "vx", "vy", "omega", "temperature", "particle_diameter"};

double& field_of(PlacedParcel& p, int column) {
  switch (column) {
    case X:
      return p.x;
    case Y:
      return p.y;
    case Diameter:
      return p.diameter;
    case Vx:
      return p.vx;
    case Vy:
      return p.vy;
    case Omega:
      return p.omega;
    case ParticleDiameter:
      return p.particle_diameter;
    default:
      return p.temperature;
  }
}

/// A comma-separated field of one line: its text without surrounding blanks and the
/// 1-based character column where that text starts.
struct Field {
  std::string_view text;
  int column = 1;
};

std::vector<Field> split_fields(std::string_view line) {
  std::vector<Field> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = std::min(line.find(',', start), line.size());
    std::size_t b = start, e = comma;
    while (b < e && (line[b] == ' ' || line[b] == '\t')) ++b;
    while (e > b && (line[e - 1] == ' ' || line[e - 1] == '\t')) --e;
    fields.push_back({line.substr(b, e - b), static_cast<int>(b) + 1});
    if (comma == line.size()) break;
    start = comma + 1;
  }
  return fields;
}

std::optional<double> parse_number(std::string_view s) {
  double v = 0.0;
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || s.empty() || !std::isfinite(v))
    return std::nullopt;
  return v;
}

class FileErrors {
 public:
  explicit FileErrors(std::string name) : name_(std::move(name)) {}
  [[noreturn]] void at(int line, int column, const std::string& what) const {
    throw SceneError(name_ + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " +
                     what);
  }

 private:
  std::string name_;
};

std::string column_list() {
  std::string s;
  for (auto n : kColumnNames) s += (s.empty() ? "" : ", ") + std::string(n);
  return s;
}

/// The column of each header field; x and y must be there, nothing twice or unknown.
std::vector<int> parse_header(const std::vector<Field>& fields, int line_no,
                              const FileErrors& error) {
  std::vector<int> layout;
  std::array<bool, kColumns> seen{};
  for (const Field& f : fields) {
    int c = 0;
    while (c < kColumns && kColumnNames[c] != f.text) ++c;
    if (c == kColumns) {
      error.at(line_no, f.column,
               "unknown column '" + std::string(f.text) + "' (known: " + column_list() + ")");
    }
    if (seen[c]) error.at(line_no, f.column, "column '" + std::string(f.text) + "' appears twice");
    seen[c] = true;
    layout.push_back(c);
  }
  for (int c : {X, Y}) {
    if (!seen[c])
      error.at(line_no, 1,
               "missing column '" + std::string(kColumnNames[c]) + "' (x and y are required)");
  }
  return layout;
}

std::string number_text(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

}  // namespace

std::vector<PlacedParcel> parse_parcel_file(const std::string& text, const std::string& name,
                                            const PlacedParcel& defaults,
                                            const ParcelFileLimits& limits) {
  const FileErrors error(name);
  std::vector<int> layout;  // column of each field, from the header
  int header_line = 0;
  std::vector<PlacedParcel> parcels;
  std::istringstream in(text);
  std::string raw;
  for (int line_no = 1; std::getline(in, raw); ++line_no) {
    std::string_view line(raw);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    const std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string_view::npos || line[first] == '#') continue;
    const std::vector<Field> fields = split_fields(line);
    if (layout.empty()) {
      header_line = line_no;
      layout = parse_header(fields, line_no, error);
      continue;
    }
    if (fields.size() != layout.size()) {
      const int column = fields.size() > layout.size() ? fields[layout.size()].column
                                                       : static_cast<int>(line.size()) + 1;
      error.at(line_no, column,
               "expected " + std::to_string(layout.size()) + " fields as in the header (line " +
                   std::to_string(header_line) + "), found " + std::to_string(fields.size()));
    }
    PlacedParcel p = defaults;
    // With a particle_diameter column each parcel holds whole particles of its own diameter.
    const bool own_particles =
        std::find(layout.begin(), layout.end(), ParticleDiameter) != layout.end();
    for (std::size_t k = 0; k < fields.size(); ++k) {
      const int c = layout[k];
      const Field& f = fields[k];
      const std::string what = "column '" + std::string(kColumnNames[c]) + "': ";
      const auto v = parse_number(f.text);
      if (!v)
        error.at(line_no, f.column, what + "'" + std::string(f.text) + "' is not a finite number");
      if ((c == Diameter || c == Temperature || c == ParticleDiameter) && !(*v > 0.0)) {
        error.at(line_no, f.column, what + "must be > 0");
      }
      if (c == X && !(*v >= limits.x_min && *v <= limits.x_max)) {
        error.at(line_no, f.column,
                 what + "parcel centre outside the grid (x from " + number_text(limits.x_min) +
                     " to " + number_text(limits.x_max) + " m)");
      }
      if (c == Y && !(*v >= limits.y_min && *v <= limits.y_max)) {
        error.at(line_no, f.column,
                 what + "parcel centre outside the grid (y from " + number_text(limits.y_min) +
                     " to " + number_text(limits.y_max) + " m)");
      }
      if (c == Diameter && !own_particles && *v < limits.min_diameter) {
        error.at(line_no, f.column,
                 what + "smaller than particles.diameter (" + number_text(limits.min_diameter) +
                     " m): a parcel holds whole particles (eq. 11)");
      }
      if ((c == Diameter || c == ParticleDiameter) && *v > limits.max_diameter) {
        error.at(line_no, f.column,
                 what + "larger than the smallest grid cell (" + number_text(limits.max_diameter) +
                     " m), which breaks the unresolved-particle model (eqs. 12-16)");
      }
      field_of(p, c) = *v;
    }
    if (own_particles) {
      std::size_t k = 0;
      while (layout[k] != ParticleDiameter) ++k;
      if (p.particle_diameter > p.diameter) {
        error.at(line_no, fields[k].column,
                 "column 'particle_diameter': larger than the parcel's diameter (" +
                     number_text(p.diameter) + " m): a parcel holds whole particles (eq. 11)");
      }
    }
    parcels.push_back(p);
  }
  if (layout.empty()) error.at(1, 1, "no header line (column names, e.g. x,y,diameter)");
  if (parcels.empty()) error.at(header_line, 1, "no parcel after the header");
  return parcels;
}

std::vector<PlacedParcel> read_parcel_file(const std::string& path, const PlacedParcel& defaults,
                                           const ParcelFileLimits& limits) {
  return parse_parcel_file(read_input_file(path, "layer file"), path, defaults, limits);
}

}  // namespace dustlift
