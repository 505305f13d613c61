#pragma once
// A minimal RAII wrapper over the HDF5 C API: create a file, write whole datasets of doubles or integers,
// and read them back (tests, restart). Errors throw std::runtime_error naming the file and dataset.
#include <cstdint>
#include <string>
#include <vector>

namespace spatula::io {

class Hdf5File {
public:
  enum class Mode { create, read, append };
  Hdf5File(const std::string& file_name, Mode mode);
  ~Hdf5File();   // closes quietly: a file written to is closed with `close`, which reports a failed flush
  void close();   // flushes and closes; throws naming the file and the reason (a full disk shows here)
  // Whether a file failed to close (its data could not be flushed: a full disk). HDF5 keeps such a file open and
  // crashes when it tries again as the library shuts down (at MPI_Finalize): a process that has seen this ends
  // without shutting HDF5 down (app: end_now).
  static bool unclosed_files();
  Hdf5File(const Hdf5File&) = delete;
  Hdf5File& operator=(const Hdf5File&) = delete;

  // Datasets are addressed by path ("/mesh/coordinates"); missing groups are created. `columns` > 1 writes a
  // row-major rows x columns table.
  void write(const std::string& path, const std::vector<double>& values, std::size_t columns = 1);
  void write(const std::string& path, const std::vector<std::int64_t>& values, std::size_t columns = 1);
  void write(const std::string& path, const std::vector<int>& values, std::size_t columns = 1);
  void write_attribute(const std::string& path, const std::string& name, double value);
  void remove(const std::string& path);   // unlinks a dataset or group (its space is not reclaimed)

  std::vector<double> read_doubles(const std::string& path) const;
  std::vector<std::int64_t> read_integers(const std::string& path) const;
  bool exists(const std::string& path) const;

  const std::string& name() const { return file_name_; }

private:
  void ensure_groups(const std::string& path);
  std::string file_name_;
  long long handle_ = -1;
};

}  // namespace spatula::io
