#pragma once
// Reads a series CSV a run writes (series/*.csv: one header row of names, then numbers;
// "nan" reads as NaN) for tests that check a run's outputs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace dustlift::testing {

struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  std::size_t column(const std::string& name) const {
    for (std::size_t k = 0; k < header.size(); ++k)
      if (header[k] == name) return k;
    ADD_FAILURE() << "no column " << name;
    return 0;
  }
};

inline Csv read_csv(const std::filesystem::path& path) {
  std::ifstream in(path);
  Csv csv;
  std::string line;
  bool first = true;
  while (std::getline(in, line)) {
    std::stringstream s(line);
    std::string cell;
    std::vector<double> row;
    while (std::getline(s, cell, ',')) {
      if (first) {
        csv.header.push_back(cell);
      } else {
        row.push_back(std::stod(cell));  // "nan" reads as NaN
      }
    }
    if (!first) csv.rows.push_back(row);
    first = false;
  }
  return csv;
}

}  // namespace dustlift::testing
