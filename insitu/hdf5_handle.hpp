#pragma once
// One owner for the ids of the HDF5 C API (files, groups, datasets, spaces, types, attributes,
// property lists): closed on scope exit, an id that failed to open thrown as `Error` with what
// was being done. The checkpoint throws CheckpointError, the series std::runtime_error.
#include <hdf5.h>

#include <string>

namespace dustlift {

template <class Error>
class Hdf5Handle {
 public:
  Hdf5Handle(hid_t id, herr_t (*close)(hid_t), const std::string& what) : id_(id), close_(close) {
    if (id_ < 0) throw Error(what);
  }
  ~Hdf5Handle() { close_(id_); }
  Hdf5Handle(const Hdf5Handle&) = delete;
  Hdf5Handle& operator=(const Hdf5Handle&) = delete;
  operator hid_t() const { return id_; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

/// Throws `Error` with `what` when an HDF5 call reports failure.
template <class Error>
void hdf5_check(herr_t status, const std::string& what) {
  if (status < 0) throw Error(what);
}

/// Silences the HDF5 error stack printout while in scope (a failed call becomes one line of
/// ours, or an expected answer such as "not an HDF5 file").
class QuietHdf5 {
 public:
  QuietHdf5() {
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietHdf5() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
  QuietHdf5(const QuietHdf5&) = delete;
  QuietHdf5& operator=(const QuietHdf5&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

}  // namespace dustlift
