// The dust-cloud series and the concentration field of a coupled run (the reduced quickstart:
// the paper's physics over a 15 mm layer): the layer's mass is the scene's rho_p alpha_p A,
// lifted + resting mass equals it at every output, and the written concentration is
// rho_p alpha_p in every cell.
#include <gtest/gtest.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkRectilinearGrid.h>
#include <vtkXMLRectilinearGridReader.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/csv.hpp"
#include "tests/support/run_cli.hpp"

namespace dustlift::testing {
namespace {

/// The reduced quickstart (a 15 mm layer in a 30 mm x 10 mm channel, to 0.1 ms) into `out`.
CliResult run_reduced_quickstart(const std::filesystem::path& out, int threads,
                                 const std::string& more = "") {
  return run_cli("run " + std::string(DUSTLIFT_SOURCE_DIR) + "/cases/quickstart.toml --out " +
                 out.string() + " --threads " + std::to_string(threads) +
                 " --set run.end_time=1e-4 --set output.interval=2.5e-5 --set grid.x.start=-0.010"
                 " --set grid.x.end=0.020 --set grid.x.cells_below=10 --set grid.y.end=0.008"
                 " --set grid.y.uniform_end=0.006 --set grid.y.cells_above=4 --set "
                 "particles.layer.x_max=0.015" +
                 more);
}

std::string file_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(DustCloudRun, LiftedPlusRestingMassIsTheLayersMassAndTheConcentrationIsRhoAlpha) {
  const auto out = fresh_dir("dust_cloud_run");
  const CliResult r = run_reduced_quickstart(out, 2);
  ASSERT_EQ(r.exit_code, 0) << r.output;

  const Csv cloud = read_csv(out / "series" / "dust_cloud.csv");
  ASSERT_EQ(cloud.rows.size(), 5u);  // t = 0, 4 outputs
  // The generated layer holds the asked volume fraction in 3-D: rho_p alpha_p A per metre.
  const double layer_mass = 980.0 * 0.59 * 0.015 * 0.002;
  const std::size_t lifted = cloud.column("lifted_mass_kg_per_m"),
                    resting = cloud.column("resting_mass_kg_per_m"),
                    layer = cloud.column("layer_mass_kg_per_m"),
                    share = cloud.column("lifted_share_1"), shock = cloud.column("shock_x_m");
  for (const auto& row : cloud.rows) {
    EXPECT_NEAR(row[layer], layer_mass, 1e-12 * layer_mass);
    EXPECT_NEAR(row[lifted] + row[resting], row[layer], 1e-12 * layer_mass) << "t = " << row[0];
    EXPECT_DOUBLE_EQ(row[share], row[lifted] / row[layer]);
  }
  EXPECT_EQ(cloud.rows.front()[lifted], 0.0);  // the layer starts at rest below its top
  // The shock (Mach 1.44 from x = -5 mm, about 500 m/s) is at about 45 mm after 0.1 ms: out of
  // this 20 mm channel, so NaN; at 25 us it is inside, about 7 mm.
  EXPECT_NEAR(cloud.rows[1][shock], -5e-3 + 498.0 * 2.5e-5, 1.5e-3);

  // The last gas file's dust_concentration is rho_p alpha_p in every cell.
  std::filesystem::path last;
  for (const auto& e : std::filesystem::directory_iterator(out / "vtk"))
    if (e.path().filename().string().rfind("gas_", 0) == 0 && e.path().string() > last.string())
      last = e.path();
  vtkNew<vtkXMLRectilinearGridReader> reader;
  reader->SetFileName(last.string().c_str());
  reader->Update();
  vtkCellData* cd = reader->GetOutput()->GetCellData();
  vtkDataArray* c = cd->GetArray("dust_concentration");
  vtkDataArray* a = cd->GetArray("alpha_p");
  ASSERT_NE(c, nullptr);
  ASSERT_NE(a, nullptr);
  double layer_cells = 0.0;
  for (vtkIdType k = 0; k < c->GetNumberOfTuples(); ++k) {
    EXPECT_EQ(c->GetTuple1(k), 980.0 * a->GetTuple1(k)) << "cell " << k;
    layer_cells += c->GetTuple1(k) > 100.0;
  }
  EXPECT_GT(layer_cells, 100.0);  // the layer's cells hold hundreds of kg/m^3
}

// In a run, the entrainment rates integrated over the outputs' intervals are the lifted mass,
// whole and stretch by stretch; the series are the same on 1 and 2 threads, byte for byte.
TEST(DustCloudRun, EntrainmentIntegratesToTheLiftedMassAndOneAndTwoThreadsAgree) {
  const auto one = fresh_dir("dust_cloud_run_t1"), two = fresh_dir("dust_cloud_run_t2");
  // A finer output interval: the rates are over the intervals between outputs.
  const std::string more = " --set output.interval=1e-5 --set output.vtk=false";
  CliResult r = run_reduced_quickstart(one, 1, more);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_reduced_quickstart(two, 2, more);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* series :
       {"dust_cloud.csv", "dust_entrainment.csv", "dust_concentration_histogram.csv"})
    EXPECT_EQ(file_bytes(one / "series" / series), file_bytes(two / "series" / series)) << series;

  const Csv cloud = read_csv(one / "series" / "dust_cloud.csv");
  const std::size_t t = cloud.column("time_s"), lifted = cloud.column("lifted_mass_kg_per_m"),
                    rate = cloud.column("entrainment_rate_kg_per_m_s"),
                    above = cloud.column("mass_above_h0p001_kg_per_m"),
                    flux = cloud.column("flux_at_h0p001_kg_per_m_s");
  ASSERT_EQ(cloud.rows.size(), 11u);
  double integral = 0.0, through = 0.0;
  for (std::size_t k = 1; k < cloud.rows.size(); ++k) {
    const double dt = cloud.rows[k][t] - cloud.rows[k - 1][t];
    integral += cloud.rows[k][rate] * dt;
    through += cloud.rows[k][flux] * dt;
  }
  const double m = cloud.rows.back()[lifted];
  ASSERT_GT(m, 0.0);
  EXPECT_NEAR(integral, m, 1e-9 * m);
  EXPECT_NEAR(through, cloud.rows.back()[above], 1e-9 * m);

  // Stretch by stretch (bins of a fortieth of the 15 mm layer, 0.375 mm): the rates per metre
  // of layer times the bins' lengths and the intervals add up to the same mass.
  const Csv stretches = read_csv(one / "series" / "dust_entrainment.csv");
  const std::size_t st = stretches.column("time_s"),
                    e = stretches.column("entrainment_rate_kg_per_m2_s");
  double binned = 0.0, previous = 0.0;
  for (const auto& row : stretches.rows) {
    for (std::size_t k = 1; k < cloud.rows.size(); ++k)
      if (cloud.rows[k][t] == row[st]) previous = cloud.rows[k - 1][t];
    binned += row[e] * 0.015 / 40.0 * (row[st] - previous);
  }
  EXPECT_NEAR(binned, m, 1e-9 * m);  // parcels start in whole bins: 0.375 mm to round-off
}

}  // namespace
}  // namespace dustlift::testing
