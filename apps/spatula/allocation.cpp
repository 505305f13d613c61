// The program's operator new: the standard one, but a failure says how much was asked for (solvers::OutOfMemory,
// a std::bad_alloc), so that an allocation failure anywhere (Tpetra, the multigrid, the program's own vectors) ends
// the run with "out of memory" and the size, not a bare std::bad_alloc. The array, nothrow and sized forms of the
// standard library forward here; delete is the standard one (free).
#include "solvers/out_of_memory.hpp"

#include <cstdlib>
#include <new>

void* operator new(std::size_t size)
{
  if (void* memory = std::malloc(size == 0 ? 1 : size)) return memory;
  throw spatula::solvers::OutOfMemory("an allocation of the program or a library it calls", double(size), false);
}
