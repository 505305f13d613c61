#pragma once
// The Tpetra types used throughout: double scalars, int local and Tpetra's default global ordinals, the default
// Kokkos node (Serial in Debian's build; the same source compiles for OpenMP or CUDA nodes).
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_FECrsGraph.hpp>
#include <Tpetra_FECrsMatrix.hpp>
#include <Tpetra_FEMultiVector.hpp>
#include <Tpetra_Map.hpp>
#include <Tpetra_Vector.hpp>

namespace spatula::discretization {

using Scalar = double;
using LocalOrdinal = Tpetra::Map<>::local_ordinal_type;
using GlobalOrdinal = Tpetra::Map<>::global_ordinal_type;
using Node = Tpetra::Map<>::node_type;
using Map = Tpetra::Map<LocalOrdinal, GlobalOrdinal, Node>;
using Import = Tpetra::Import<LocalOrdinal, GlobalOrdinal, Node>;
using Vector = Tpetra::Vector<Scalar, LocalOrdinal, GlobalOrdinal, Node>;
using MultiVector = Tpetra::MultiVector<Scalar, LocalOrdinal, GlobalOrdinal, Node>;
using CrsMatrix = Tpetra::CrsMatrix<Scalar, LocalOrdinal, GlobalOrdinal, Node>;
using FECrsGraph = Tpetra::FECrsGraph<LocalOrdinal, GlobalOrdinal, Node>;
using FECrsMatrix = Tpetra::FECrsMatrix<Scalar, LocalOrdinal, GlobalOrdinal, Node>;
using FEMultiVector = Tpetra::FEMultiVector<Scalar, LocalOrdinal, GlobalOrdinal, Node>;
using Operator = Tpetra::Operator<Scalar, LocalOrdinal, GlobalOrdinal, Node>;
using device_type = Node::device_type;
using execution_space = device_type::execution_space;
template <class T>
using DeviceView = Kokkos::View<T, device_type>;   // a view in the memory the kernels run on

}  // namespace spatula::discretization
