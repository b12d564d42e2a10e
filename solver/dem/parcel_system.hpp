#pragma once
// Coarse-grained DEM parcels (paper eqs. 5–6, 11, 18; docs/dem.md) as
// structure-of-arrays, with a cell-sorted Verlet neighbour list that carries the
// per-pair tangential history, axis-aligned walls, optional periodicity in x, and
// symplectic Euler sub-steps.
//
// Units: 2-D, per metre of depth. A parcel stands for n_real real particles (per metre);
// its mass and inertia are the sums over them. Every force part stored here is per REAL
// particle (the parcel's total is n_real times it): eq. (5) divided by n_i, which is how
// the paper integrates parcels (acceleration = real-particle force / real-particle mass).
// Where parcels of different real counts touch, a pair stands for min(n_i, n_j) real
// contacts, so that their total forces stay equal and opposite (docs/dem.md).
//
// Determinism: every parcel gathers its own contacts in neighbour-list order (each pair is
// evaluated from both sides, bitwise symmetrically); no atomics, no reductions other than
// max. Results are identical for any OpenMP thread count.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "solver/core/parallel_minimum.hpp"
#include "solver/core/phase_timer.hpp"
#include "solver/dem/dem_config.hpp"
#include "solver/dem/forced_euler.hpp"
#include "solver/dem/parcel_forcing.hpp"
#include "solver/dem/parcel_ranks.hpp"
#include "solver/dem/parcel_table.hpp"

namespace dustlift {

/// One parcel to add (before the first step).
struct ParcelInit {
  double x = 0.0, y = 0.0;        ///< m
  double vx = 0.0, vy = 0.0;      ///< m/s
  double omega = 0.0;             ///< rad/s, counter-clockwise positive (right-handed z)
  double diameter = 100e-6;       ///< m, parcel diameter n_xy d
  double real_diameter = 100e-6;  ///< m, real particle diameter d
  double density = 980.0;         ///< kg/m^3 of the real particles
  double n_real = 1.0;            ///< real particles per parcel (per metre of depth)
  double temperature = 300.0;     ///< K
  int size_class = 0;             ///< the layer's size class (DemConfig::size_classes)
};

/// The DEM's own counters and decisions, for checkpoints: with the parcel table's checkpointed
/// columns and the contact history they continue a run bitwise.
struct ParcelInternals {
  bool needs_rebuild = true;
  double time = 0.0;
  long long steps = 0, rebuilds = 0;
  double gravity_x = 0.0, gravity_y = 0.0;  ///< may differ from the scene (set_gravity)
};

class ParcelSystem : public ParcelTable {
 public:
  /// Contact laws, walls, domain, gravity, skin and heat capacity come from `cfg`;
  /// the parcels are added with add_parcel (see make_paper_layer in layer_generator.hpp).
  explicit ParcelSystem(const DemConfig& cfg);

  void reserve(std::size_t n);
  /// Adds one parcel; its id is the running count. Invalidates the neighbour list.
  void add_parcel(const ParcelInit& p);

  /// Eq. (18): nu_DEM sqrt(min real-particle mass / max spring constant).
  double stable_time_step() const;

  /// One symplectic Euler step (v^{n+1} = v^n + dt F^n/m, x^{n+1} = x^n + dt v^{n+1}) under
  /// the contacts (recomputed), gravity and, when set, the forcing (set_forcing).
  void step(double dt);

  /// Called before every sub-step with (system, sub-step time) so the coupling can fill
  /// the drag/Magnus/pressure/fluid-torque/heat arrays.
  using SubstepHook = std::function<void(ParcelSystem&, double)>;
  /// n = ceil(dt_total / stable_time_step()): the sub-steps advance() takes for dt_total.
  int substeps_for(double dt_total) const;
  /// Advances by dt_total in n = substeps_for(dt_total) equal sub-steps.
  /// Returns n.
  int advance(double dt_total, const SubstepHook& hook = {});

  /// Kinetic (translation + rotation) energy, J per metre of depth (sum over real particles).
  double kinetic_energy() const;
  /// Kinetic + elastic (contact springs, from the current overlaps and stored tangential
  /// elongations) + gravitational potential, minus the cohesion's work over the overlaps,
  /// J per metre of depth.
  double mechanical_energy() const;
  /// Number of parcel–parcel pairs in contact (each counted once) at the current positions.
  std::size_t contact_pair_count() const;

  /// How the contact pass walks the neighbour list: per chunk of parcels, slot by slot where
  /// few of its listed pairs touched in the last pass and parcel by parcel where many did
  /// (Adaptive, what runs), or one way throughout. All three give the same bits.
  enum class ContactTraversal { Adaptive, ByParcel, BySlot };
  void set_contact_traversal(ContactTraversal t) { traversal_ = t; }

  double time() const { return time_; }
  long long steps() const { return steps_; }
  long long neighbour_rebuilds() const { return rebuilds_; }
  /// Parcels whose neighbour list a rebuild kept from the one before (kept_lists.cpp), summed
  /// over the rebuilds since construction.
  long long kept_lists() const { return kept_lists_; }
  /// Whether rebuilds keep the lists of parcels whose neighbourhood did not change (on by
  /// default; the lists are the same either way, so off only to check that).
  void set_keep_unchanged_lists(bool keep) { keep_unchanged_lists_ = keep; }
  /// How often the parcel data were re-sorted (every column permuted) since construction:
  /// parcel indices are stable between two of them.
  long long data_permutations() const { return data_permutations_; }
  /// Parcel-sub-steps computed (sub-steps times the parcels stepped in each).
  long long parcel_substeps() const { return parcel_substeps_; }
  /// Wall seconds spent in the contact pass, the integration and the neighbour rebuilds.
  struct Timings {
    double contacts = 0.0, integrate = 0.0, rebuild = 0.0;
  };
  const Timings& timings() const { return timings_; }
  const DemConfig& config() const { return cfg_; }
  /// Changes the body acceleration (e.g. gravity only while a bed settles).
  void set_gravity(double gx, double gy) {
    cfg_.gravity_x = gx;
    cfg_.gravity_y = gy;
  }

  /// Forces a neighbour rebuild (and cell re-sort) before the next step.
  void invalidate_neighbours() { needs_rebuild_ = true; }
  /// Sorts the parcels by cell and builds the neighbour list now if it is due (the coupling
  /// does this before its first deposit, so that the deposit order of parcels at rest never
  /// changes afterwards: a resting layer then deposits the same alpha_p to the last bit).
  void build_neighbours_if_due() {
    if (needs_rebuild_) rebuild_neighbours();
  }

  /// Sets what moves the parcels besides contacts and gravity (the coupling's gas-particle
  /// effects, once; shared by copies of this system). Its columns must be attached here.
  void set_forcing(std::shared_ptr<const ParcelForcing> f) { forcing_ = std::move(f); }
  /// The columns a forced sub-step integrates (forced_euler.hpp), without exchange sums.
  EulerArrays euler_arrays();
  /// Marks the next advance() to store the force parts, relative rotation and heat rate of
  /// its last sub-step in their columns (the observers' view); other sub-steps skip those
  /// stores. Default: always stored.
  void store_parts_on_last_substep_only(bool on) { parts_last_only_ = on; }

  /// Limits the sub-steps to the parcels up to the last one whose `stepped` column value is
  /// non-zero (the coupling marks those that may move this CFD step; those after them rest
  /// exactly and would not change a bit). Re-read at every advance and after every re-sort.
  /// An invalid handle (the default) steps every parcel.
  void set_stepped_column(ParcelColumn stepped) { stepped_ = stepped; }
  /// Parcels the current sub-steps run over: [0, stepped_count()).
  std::size_t stepped_count() const { return stepped_count_ < size() ? stepped_count_ : size(); }

  // ---- Parcels split over ranks (solver/parallel/parcel_slabs.hpp splits them) ----
  bool decomposed() const { return ranks_ != nullptr; }
  /// From now on `ranks` splits the parcels (it must outlive the split): the rebuilds, the
  /// sub-step decisions and the rank copies go through it. drop_decomposition undoes it.
  void decompose(ParcelRanks& ranks);
  /// Collective when split: the rank copies take their owners' values of these attached columns
  /// now (the coupling's samples and exchange sums, which the owners compute).
  void refresh_rank_copies(std::span<const ParcelColumn> columns);
  /// Back to a one-rank system's bookkeeping (the table is left as it is): a restart first
  /// takes the whole checkpointed system into a copy of this one, then splits it again.
  void drop_decomposition();
  /// Parcels this rank owns (size() in a one-rank run).
  std::size_t owned_count() const;

  // ---- Whole parcels between tables (parcel_packing.cpp) ----
  /// Appends every owned parcel's full state (all columns and its contact history as
  /// partner ids and elongations) to `out`, in parcel order: what moves with a parcel to
  /// another rank, and what a checkpoint gathers. Without the history (`with_history`
  /// false) the packed parcels carry no contact history (an observer's view: cheaper to
  /// gather and to assign). `keep`, when given, picks the parcels (by index) to pack.
  void pack_owned(std::vector<double>& out, bool with_history = true,
                  const std::function<bool(std::size_t)>& keep = {}) const;
  /// A one-rank system from packed parcels (pack_owned of every rank, any order): sorted by
  /// order key, with each parcel's contact history as its neighbour list, so that it
  /// continues as the decomposed run would (checkpoints, tests). The attached columns must
  /// be attached (same specs, same order) before.
  void assign_packed(const std::vector<std::vector<double>>& pieces);
  /// One parcel packed (pack_row and its contact history).
  void pack_parcel(std::size_t i, bool with_history, std::vector<double>& out) const;
  /// Appends a packed parcel; returns the next row; its history goes to the carried history.
  const double* append_packed(const double* row, bool copy);
  /// New row k = old row source[k], for every moved column and the carried history.
  void reorder_parcels(const std::vector<std::int32_t>& source);
  /// Sorts the table by order key; returns the rows' old indices in their new order.
  std::vector<std::int32_t> sort_table_by_key();
  /// Every row carries no contact history.
  void clear_carried_history();
  /// Each own parcel's listed partners (by id) and elongations become the history its row
  /// carries (rank copies carry none); the list must be current.
  void carry_listed_history();

  // ---- The neighbour cells, which a split over ranks cuts along ----
  /// Sizes the cells for the current parcels (at least the largest cutoff, over every rank's
  /// parcels); every rebuild does this first.
  void update_cell_geometry();
  int cell_columns() const { return cells_x_; }
  double cell_width() const { return cell_dx_; }
  /// Whether the cells are numbered along y first (the domain is longer than high).
  bool cells_along_y_first() const { return x_major_; }
  /// The cell column of x as the cell sort finds it (so a split and the cells agree).
  int cell_column(double px) const {
    return std::clamp(static_cast<int>(std::floor((px - cfg_.domain.x_min) / cell_dx_)), 0,
                      cells_x_ - 1);
  }
  /// Collective when split: the largest centre distance at which a rebuild may list a pair
  /// now, from the skins any own parcel may get or still move by.
  double listing_reach() const;

  /// Checkpoint access to the DEM's counters (see ParcelInternals).
  ParcelInternals internals() const;
  /// Restores them after the table's columns and the contact history have been restored;
  /// throws std::invalid_argument when a column does not match size() or the contact
  /// history is inconsistent. A rebuilt column not made (empty) asks for a rebuild.
  void restore_internals(const ParcelInternals& s);

  // ---- Contact history (serialisable for checkpoints) ----
  /// Neighbour list in CSR form: parcel i's candidates are slots
  /// nbr_offset[i] .. nbr_offset[i+1]-1; nbr_index is the partner's current index,
  /// nbr_image its periodic image (partner x seen from i = x[j] + image * L_x) and
  /// nbr_delta the tangential spring elongation of the pair (0 when not touching).
  std::vector<std::int32_t> nbr_offset, nbr_index;
  std::vector<std::int8_t> nbr_image;
  std::vector<double> nbr_delta;

 private:
  void step_with_parts(double dt, bool store_parts);
  void rebuild_neighbours();
  /// Per-parcel skins: the base skin/2, the time a fast parcel's skin covers at its speed,
  /// and the cap (after update_cell_geometry).
  struct SkinLimits {
    double base = 0.0, time = 0.0, cap = 0.0;
  };
  SkinLimits skin_limits() const;
  // rebuild_neighbours' steps (neighbour_list.cpp), in order.
  /// One rank: the old list's history by partner id in old_*.
  void key_history_by_partner_id();
  /// Each parcel's skin (half_skin) and the fast parcels (fast_); returns the largest skin.
  double assign_skins(const SkinLimits& limits);
  /// The fast parcels' pairs (fast_pairs_), found in a block wide enough for any partner.
  void list_fast_pairs(double s_max);
  /// Where each parcel's fast pairs start, and its slow side's extra slots for them.
  void index_fast_pairs(double s_base);
  /// Which parcels keep their list of the last build (keeps_list_, kept_lists.cpp): `possible`
  /// when the cells, the parcel order and the reach are those of the last build.
  void mark_kept_lists(bool possible, double s_base);
  /// The new list (nbr_*), with the history of pairs listed before when there was a list.
  void list_partners(double s_base, bool had_list);
  /// list_partners' per-range steps: the partners of range t of `ranges` into its buffer,
  /// then the buffer into the list's slots.
  void list_range(int t, int ranges, double s_base);
  void fill_range(int t, int ranges, bool had_list);
  /// The walls each parcel may touch before the next rebuild (wall_mask).
  void mask_walls();
  /// The positions of this build and the skins' inverse squares (x_build, y_build, inv_skin2).
  void mark_build_positions(bool distributed);
  /// Calls f(j, image) for the parcels in the cells within `block` cells of parcel i's cell,
  /// in a fixed order (major axis outer, minor inner, parcels in cell order).
  template <class F>
  void for_each_nearby(std::size_t i, int block, F&& f) const;
  /// Whether pair (i, j at periodic image `image`) lies within the two skins and the units' reach.
  bool within_listing_reach(std::size_t i, std::int32_t j, int image) const;
  /// Calls f(j, image) for every partner a rebuild lists for parcel i.
  template <class F>
  void for_each_partner(std::size_t i, double s_base, F&& f) const;
  void sort_by_cell(bool permute_data);
  void compute_contacts(double dt);
  /// The contact pass. Mixed: parcels of different real counts meet (the pair rule);
  /// PairDamping: a restitution is given, so the dashpot follows each pair's reduced mass;
  /// units: the active contact units (contact_effects/, e.g. cohesion), whose forces it adds.
  /// A pass without an option or a unit compiles none of its code.
  template <bool Mixed, bool PairDamping, class... Units>
  void contacts_pass(double dt, const Units&... units);
  bool mixed_counts_ = false;  ///< some parcels' real counts differ (valid when counts_known_)
  bool counts_known_ = false;  ///< cleared when parcels are added, restored or moved
  /// c(e) of the parcel-parcel and parcel-wall restitutions (contact.hpp; used when given).
  double pair_damping_factor_ = 0.0, wall_damping_factor_ = 0.0;
  /// How far beyond touching the active contact units reach (e.g. the cohesion's cut-off): the
  /// neighbour list, the wall mask and the rank copies look that much further.
  double pair_reach_ = 0.0, wall_reach_ = 0.0;
  void integrate(double dt, bool store_parts);
  double wall_position(int w) const;

  DemConfig cfg_;
  double length_x_ = 0.0;  ///< periodic length
  double skin_ = 0.0;      ///< m, absolute
  bool needs_rebuild_ = true;
  double time_ = 0.0;
  long long steps_ = 0;
  long long rebuilds_ = 0;
  long long data_permutations_ = 0;
  long long parcel_substeps_ = 0;

  std::shared_ptr<const ParcelForcing> forcing_;
  bool parts_last_only_ = false;
  /// Contact pass: parcels per chunk, and the pairs each chunk found touching in the last
  /// pass (which way the next pass computes it; dem_step.cpp).
  static constexpr std::size_t kContactChunk = 1024;
  std::vector<std::int32_t> chunk_touching_;
  ContactTraversal traversal_ = ContactTraversal::Adaptive;
  ParcelColumn stepped_;
  std::size_t stepped_count_ = static_cast<std::size_t>(-1);
  void update_stepped_count();
  Timings timings_;

  // Cell grid of the last rebuild.
  int cells_x_ = 1, cells_y_ = 1;
  bool x_major_ = true;  ///< cells numbered along y first (x is the long axis)
  /// The cells stored: columns [box_x0_, box_x0_ + box_nx_) x rows [box_y0_, box_y0_ + box_ny_)
  /// of the domain's cells, those the parcels occupied at the last sort.
  int box_x0_ = 0, box_y0_ = 0, box_nx_ = 1, box_ny_ = 1;
  bool in_box(int cx, int cy) const {
    return cx >= box_x0_ && cx < box_x0_ + box_nx_ && cy >= box_y0_ && cy < box_y0_ + box_ny_;
  }
  /// Index of domain cell (cx, cy) inside the box, numbered in the domain's order.
  int cell_index(int cx, int cy) const {
    return x_major_ ? (cx - box_x0_) * box_ny_ + (cy - box_y0_)
                    : (cy - box_y0_) * box_nx_ + (cx - box_x0_);
  }
  /// The cell row of y as the cell sort finds it (with cell_column: the sort and the list
  /// keeping must agree on a parcel's cell; clamping is monotone and contracting, so parcels
  /// outside the domain stay correct).
  int cell_row(double py) const {
    return std::clamp(static_cast<int>(std::floor((py - cfg_.domain.y_min) / cell_dy_)), 0,
                      cells_y_ - 1);
  }
  /// Calls f(rx, ry, image) for the stored cells within `block` cells of the cell holding
  /// box index c, major axis outer, minor inner; image is the periodic image (-1, 0, 1) a
  /// wrapped cell is seen at.
  template <class F>
  void for_each_cell_near(int c, int block, F&& f) const {
    const int cx = box_x0_ + (x_major_ ? c / box_ny_ : c % box_nx_);
    const int cy = box_y0_ + (x_major_ ? c % box_ny_ : c / box_nx_);
    for (int outer = -block; outer <= block; ++outer) {
      for (int inner = -block; inner <= block; ++inner) {
        const int ry = cy + (x_major_ ? inner : outer);
        if (ry < 0 || ry >= cells_y_) continue;
        int rx = cx + (x_major_ ? outer : inner);
        int image = 0;
        if (rx < 0 || rx >= cells_x_) {
          if (!cfg_.domain.periodic_x) continue;
          image = rx < 0 ? -1 : 1;
          rx -= image * cells_x_;
        }
        if (in_box(rx, ry)) f(rx, ry, image);  // outside the box: no parcels there
      }
    }
  }
  double cell_dx_ = 1.0, cell_dy_ = 1.0;
  std::vector<std::int32_t> cell_of_, cell_start_, order_;
  std::vector<std::int32_t> cell_y_;     ///< sort scratch: each parcel's cell row
  std::vector<std::int32_t> members_;    ///< parcels of each cell: members_[cell_start_[c] ..]
  std::vector<std::int32_t> cursor_;     ///< counting-sort fill positions, one per cell
  std::vector<std::int32_t> old_index_;  ///< index before the last rebuild, per parcel

  // Per-parcel skins of the last rebuild (half_skin_: how far the parcel may move) and the
  // fast parcels' pairs (see rebuild_neighbours).
  struct FastPair {
    std::int32_t i, j;
    std::int8_t image;
  };
  std::vector<std::int32_t> fast_, fast_start_, extra_start_;
  std::vector<FastPair> fast_pairs_, extra_pairs_;
  std::vector<std::vector<FastPair>> fast_pairs_by_thread_;
  struct ListedPartner {
    std::int32_t j;
    std::int8_t image;
  };
  std::vector<std::vector<ListedPartner>>
      list_by_range_;  ///< rebuild scratch, one per range of parcels (one per thread)
  double radius_max_ = 0.0, cutoff_ = 0.0;

  // Lists kept from the last build (kept_lists.cpp): a parcel that has not moved, whose skin
  // is the same and whose 3x3 cells hold the same unmoved parcels lists the same partners in
  // the same order, so its slots are copied instead of searched again.
  bool keep_unchanged_lists_ = true;
  long long kept_lists_ = 0;
  std::vector<std::uint8_t> keeps_list_;  ///< per parcel, this rebuild (empty: none kept)
  /// Per parcel: fast, or the partner of a fast parcel (its list has slots a 3x3 search does
  /// not give), at this build and at the last one.
  std::vector<std::uint8_t> near_fast_, near_fast_before_;
  std::vector<std::uint8_t> changed_parcels_;  ///< moved or reskinned since the last build
  std::vector<std::uint8_t> changed_near_;     ///< per cell of the box: within a cell of a change
  std::vector<double> skin_before_;            ///< half_skin of the last build
  std::vector<std::int32_t> old_nbr_index_;    ///< the last build's list (indices unchanged)
  std::vector<std::int8_t> old_nbr_image_;
  /// The cells and reach the last list was made with.
  struct ListingGeometry {
    int cells_x = 0, cells_y = 0;
    double cell_dx = 0.0, cell_dy = 0.0, pair_reach = -1.0;
    bool operator==(const ListingGeometry&) const = default;
  };
  ListingGeometry listed_geometry_;

  // Rebuild scratch (kept to avoid reallocation).
  std::vector<std::int32_t> scratch_i_;
  std::vector<std::int32_t> old_offset_, old_partner_id_;
  std::vector<double> old_delta_;

  ParcelRanks* ranks_ = nullptr;  ///< the split over ranks; null on one rank
  // The carried history of the rows while parcels move (CSR over the rows, partner ids).
  std::vector<std::int32_t> hist_offset_, hist_partner_;  ///< carried history, per table row
  std::vector<double> hist_delta_;
};

}  // namespace dustlift
