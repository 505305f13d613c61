#include "io/hdf5_file.hpp"

#include <hdf5.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace spatula::io {

namespace {

// The system's reason of the failed call, where it set one (a full disk: "No space left on device").
std::string system_reason()
{
  return errno != 0 ? std::string(": ") + std::strerror(errno) : std::string();
}

[[noreturn]] void fail(const std::string& what, const std::string& file, const std::string& path)
{
  throw std::runtime_error("HDF5: cannot " + what + " '" + path + "' in '" + file + "'" + system_reason());
}

template <class T>
hid_t memory_type();
template <>
hid_t memory_type<double>() { return H5T_NATIVE_DOUBLE; }
template <>
hid_t memory_type<std::int64_t>() { return H5T_NATIVE_INT64; }
template <>
hid_t memory_type<int>() { return H5T_NATIVE_INT; }

template <class T>
void write_dataset(hid_t file, const std::string& file_name, const std::string& path, const std::vector<T>& values,
                   std::size_t columns)
{
  errno = 0;
  const hsize_t dims[2] = {columns > 1 ? values.size() / columns : values.size(), columns};
  const hid_t space = H5Screate_simple(columns > 1 ? 2 : 1, dims, nullptr);
  const hid_t set = H5Dcreate2(file, path.c_str(), memory_type<T>(), space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (set < 0) {
    H5Sclose(space);
    fail("create dataset", file_name, path);
  }
  const herr_t status =
      values.empty() ? 0 : H5Dwrite(set, memory_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  H5Dclose(set);
  H5Sclose(space);
  if (status < 0) fail("write dataset", file_name, path);
}

template <class T>
std::vector<T> read_dataset(hid_t file, const std::string& file_name, const std::string& path)
{
  const hid_t set = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  if (set < 0) fail("open dataset", file_name, path);
  const hid_t space = H5Dget_space(set);
  const hssize_t count = H5Sget_simple_extent_npoints(space);
  std::vector<T> values(static_cast<std::size_t>(count));
  const herr_t status =
      values.empty() ? 0 : H5Dread(set, memory_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  H5Sclose(space);
  H5Dclose(set);
  if (status < 0) fail("read dataset", file_name, path);
  return values;
}

bool unclosed = false;

}  // namespace

bool Hdf5File::unclosed_files() { return unclosed; }

Hdf5File::Hdf5File(const std::string& file_name, Mode mode) : file_name_(file_name)
{
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);   // errors become exceptions, not stderr noise
  errno = 0;
  handle_ = mode == Mode::create ? H5Fcreate(file_name.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT)
            : H5Fopen(file_name.c_str(), mode == Mode::read ? H5F_ACC_RDONLY : H5F_ACC_RDWR, H5P_DEFAULT);
  if (handle_ < 0)
    throw std::runtime_error("HDF5: cannot " + std::string(mode == Mode::create ? "create" : "open") + " file '" +
                             file_name + "'" + system_reason());
}

Hdf5File::~Hdf5File()
{
  if (handle_ >= 0 && H5Fclose(static_cast<hid_t>(handle_)) < 0) unclosed = true;
}

void Hdf5File::close()
{
  errno = 0;
  const hid_t handle = static_cast<hid_t>(handle_);
  handle_ = -1;
  const herr_t flushed = H5Fflush(handle, H5F_SCOPE_LOCAL);
  const std::string reason = system_reason();
  const herr_t closed = H5Fclose(handle);
  if (closed < 0) unclosed = true;
  if (flushed < 0 || closed < 0)
    throw std::runtime_error("HDF5: cannot write file '" + file_name_ + "'" + (reason.empty() ? system_reason() : reason));
}

void Hdf5File::ensure_groups(const std::string& path)
{
  for (std::size_t slash = path.find('/', 1); slash != std::string::npos; slash = path.find('/', slash + 1)) {
    const std::string group = path.substr(0, slash);
    if (H5Lexists(static_cast<hid_t>(handle_), group.c_str(), H5P_DEFAULT) > 0) continue;
    const hid_t id = H5Gcreate2(static_cast<hid_t>(handle_), group.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (id < 0) fail("create group", file_name_, group);
    H5Gclose(id);
  }
}

void Hdf5File::write(const std::string& path, const std::vector<double>& values, std::size_t columns)
{
  ensure_groups(path);
  write_dataset(static_cast<hid_t>(handle_), file_name_, path, values, columns);
}

void Hdf5File::write(const std::string& path, const std::vector<std::int64_t>& values, std::size_t columns)
{
  ensure_groups(path);
  write_dataset(static_cast<hid_t>(handle_), file_name_, path, values, columns);
}

void Hdf5File::write(const std::string& path, const std::vector<int>& values, std::size_t columns)
{
  ensure_groups(path);
  write_dataset(static_cast<hid_t>(handle_), file_name_, path, values, columns);
}

void Hdf5File::write_attribute(const std::string& path, const std::string& name, double value)
{
  const hid_t object = H5Oopen(static_cast<hid_t>(handle_), path.c_str(), H5P_DEFAULT);
  if (object < 0) fail("open object", file_name_, path);
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t attribute = H5Acreate2(object, name.c_str(), H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT);
  const herr_t status = attribute < 0 ? -1 : H5Awrite(attribute, H5T_NATIVE_DOUBLE, &value);
  if (attribute >= 0) H5Aclose(attribute);
  H5Sclose(space);
  H5Oclose(object);
  if (status < 0) fail("write attribute " + name + " of", file_name_, path);
}

std::vector<double> Hdf5File::read_doubles(const std::string& path) const
{
  return read_dataset<double>(static_cast<hid_t>(handle_), file_name_, path);
}

std::vector<std::int64_t> Hdf5File::read_integers(const std::string& path) const
{
  return read_dataset<std::int64_t>(static_cast<hid_t>(handle_), file_name_, path);
}

void Hdf5File::remove(const std::string& path)
{
  if (H5Ldelete(static_cast<hid_t>(handle_), path.c_str(), H5P_DEFAULT) < 0) fail("remove", file_name_, path);
}

bool Hdf5File::exists(const std::string& path) const
{
  std::size_t slash = 0;
  while ((slash = path.find('/', slash + 1)) != std::string::npos)
    if (H5Lexists(static_cast<hid_t>(handle_), path.substr(0, slash).c_str(), H5P_DEFAULT) <= 0) return false;
  return H5Lexists(static_cast<hid_t>(handle_), path.c_str(), H5P_DEFAULT) > 0;
}

}  // namespace spatula::io
