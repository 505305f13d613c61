#pragma once
// A failed allocation, named as such: what was being allocated and how much. It is a std::bad_alloc, so that the one
// rule "an allocation failure is never a numerical failure" is one catch clause wherever a solver turns exceptions
// into a retry (Newton's step cut, the jump's shift, the arc-length's stop): `catch (const std::bad_alloc&) { throw; }`
// before `catch (const std::exception&)`. Kokkos' RawMemoryAllocationFailure is one too.
#include <new>
#include <string>

namespace spatula::solvers {

class OutOfMemory : public std::bad_alloc {
public:
  // `what`: the allocation ("MUMPS factorization workspace"); `bytes`: its size (0: unknown); `collective`: every
  // rank fails together (MUMPS reports a failure on one rank to all), so that the run can still write its last state.
  OutOfMemory(const std::string& what, double bytes, bool collective);
  const char* what() const noexcept override { return message_.c_str(); }
  bool collective() const { return collective_; }

private:
  std::string message_;
  bool collective_;
};

// "1.25 GB", "310 MB", "4.0 kB": an allocation's size in a message.
std::string memory_size_text(double bytes);

}  // namespace spatula::solvers
