// Point probes as an in-situ series: what a pressure gauge in a shock tube records.
#include <memory>
#include <stdexcept>

#include "insitu/observers.hpp"
#include "insitu/series_observer.hpp"
#include "solver/sim/time_targets.hpp"

namespace dustlift {
namespace {

class ProbeObserver final : public SeriesObserver {
 public:
  explicit ProbeObserver(ProbeOptions options)
      : SeriesObserver("probes"),
        options_(std::move(options)),
        table_("probes", columns(options_)),
        samples_(options_.interval > 0.0 ? Cadence::simulated(options_.interval)
                                         : Cadence::every_step()) {
    if (options_.probes.empty()) throw std::invalid_argument("ProbeObserver: no probe");
    keep({&table_});
  }

  void on_start(const StateView& view) override {
    sample(view);
    write_series(view);
  }
  bool reads_step(const StateView& view) const override {
    return samples_.due({view.time, view.step, 0.0});
  }
  unsigned step_reads() const override { return kReadsGas | kReadsAlphaP; }
  unsigned output_reads() const override { return step_reads(); }
  void on_step(const StateView& view) override {
    if (reads_step(view)) sample(view);
  }
  void on_output(const StateView& view) override { write_series(view); }
  void on_finish(const StateView& view) override {
    sample(view);
    write_series(view);
  }

 private:
  void save_more(Snapshot& s, const std::string& prefix) const override {
    s.i64[prefix + "next_sample"] = {samples_.next_index()};
  }
  void restore_more(const Snapshot& s, const std::string& prefix) override {
    samples_.set_next_index(snapshot_array(s.i64, prefix + "next_sample", 1)[0]);
  }
  static std::vector<SeriesColumn> columns(const ProbeOptions& o) {
    std::vector<SeriesColumn> c{{"time", "s"}};
    for (const ProbeConfig& p : o.probes) {
      for (const std::string& f : p.fields) {
        for (const ProbeField& known : kProbeFields) {
          if (f == known.name) c.push_back({p.name + "_" + f, known.unit});
        }
      }
    }
    return c;
  }
  double value(const StateView& v, const std::string& field, int i, int j) const {
    const GasPrimitives& g = v.primitives;
    if (field == "p") return (*g.p)(i, j);
    if (field == "rho") return (*g.rho)(i, j);
    if (field == "u") return (*g.u)(i, j);
    if (field == "v") return (*g.v)(i, j);
    if (field == "T") return (*g.T)(i, j);
    if (field == "alpha_p")
      return v.alpha_p != nullptr ? (*v.alpha_p)(i, j) : 1.0 - (*g.alpha_g)(i, j);
    if (!v.gas) throw std::invalid_argument("ProbeObserver: the Mach number needs the gas solver");
    return std::hypot((*g.u)(i, j), (*g.v)(i, j)) / v.gas->sound_speed(i, j);  // "mach"
  }
  void sample(const StateView& view) {
    if (sampled_at(view.time)) return;
    if (!view.grid || !view.primitives.p)
      throw std::invalid_argument("ProbeObserver: the state view has no gas fields");
    row_.assign(1, view.time);
    for (const ProbeConfig& p : options_.probes) {
      const int i = view.grid->x().locate(p.x), j = view.grid->y().locate(p.y);
      for (const std::string& f : p.fields) row_.push_back(value(view, f, i, j));
    }
    table_.append_row(row_);
    mark_sampled(view.time);
    samples_.done({view.time, view.step, 0.0});
  }

  ProbeOptions options_;
  SeriesTable table_;
  std::vector<double> row_;
  Cadence samples_;  ///< probe.interval, or every step
};

}  // namespace

std::unique_ptr<Observer> make_probe_observer(ProbeOptions options) {
  return std::make_unique<ProbeObserver>(std::move(options));
}

}  // namespace dustlift
