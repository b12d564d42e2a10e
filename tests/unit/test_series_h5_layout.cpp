// series.h5 as an h5py user meets it: a group per series, one dataset per column with its
// units, the abscissa as the dimension scale of every other column, the column order in
// "columns", strings as str, and root attributes saying how the file was made.
#include <gtest/gtest.h>

#include <filesystem>

#include "insitu/series_table.hpp"
#include "support/run_cli.hpp"

using namespace dustlift;
using dustlift::testing::fresh_dir;
using dustlift::testing::run_command;
using dustlift::testing::write_file;

TEST(SeriesH5Layout, GroupsScalesUnitsAndRootAttributesReadWithH5py) {
  const auto dir = fresh_dir("series_h5_layout");
  SeriesSink sink(dir.string(), SeriesFileInfo{"0.1.0 (git abc)", "dustlift run s.toml --out o", "[run]\nend_time = 1.0\n"});
  SeriesTable near("near_layer", {{"time", "s"}, {"x", "m"}, {"u", "m/s"}, {"vorticity", "1/s"}});
  for (int k = 0; k < 5; ++k) {
    near.append_row(std::vector{1e-6 * k, 0.01, 3.0 * k, -2.0 * k});
    sink.write(near);
  }
  const std::string script = R"py(
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1] + "/series/series.h5", "r")
assert f.attrs["code_version"] == "0.1.0 (git abc)", f.attrs["code_version"]
assert f.attrs["command_line"] == "dustlift run s.toml --out o"
assert f.attrs["scene"].startswith("[run]")
assert f.attrs["format"] == "dustlift-series 2"
assert len(f.attrs["written_at"].decode()) == 20 and f.attrs["written_at"].decode().endswith("Z")
g = f["near_layer"]
assert g.attrs["columns"] == "time,x,u,vorticity", g.attrs["columns"]
assert g["u"].attrs["units"] == "m/s" and g["vorticity"].attrs["units"] == "1/s"
for name in ("x", "u", "vorticity"):
    assert g[name].dims[0][0].name == "/near_layer/time", (name, g[name].dims[0].keys())
assert list(g["u"][()]) == [0.0, 3.0, 6.0, 9.0, 12.0]
a = np.genfromtxt(sys.argv[1] + "/series/near_layer.csv", delimiter=",", names=True)
assert a.dtype.names == ("time_s", "x_m", "u_m_per_s", "vorticity_per_s"), a.dtype.names
assert list(a["u_m_per_s"]) == [0.0, 3.0, 6.0, 9.0, 12.0]
print("ok")
)py";
  write_file(dir / "check.py", script);
  const auto r = run_command("/usr/bin/python3 " + (dir / "check.py").string() + " " + dir.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("ok"), std::string::npos) << r.output;
  std::filesystem::remove_all(dir);
}
