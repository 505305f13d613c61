#pragma once
// The bulk solid, chosen by name like the contact laws: its parameters (SolidParameters, the 'Material' list), the
// SolidModel that integrates this rank's Hex8 and Hex13 elements with a hyperelastic law into the global system and
// gives the element field tr(sigma), LawSolidModel<Law> for any law that is a pure function of F (evaluate(F, W, P,
// A) and cauchy(F, sigma), as laws::NeoHookean), and the registry that turns 'Material/law' into a model: a second
// law is one header in packages/laws and one line in SolidLawRegistry's constructor (solid_model.cpp).
#include "discretization/solid_kernel.hpp"

#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace spatula::discretization {

struct SolidParameters {
  std::string law = "neo-hookean";   // a name of SolidLawRegistry
  double young = 2.0;     // E [GPa] = [nN / nm^2]
  double poisson = 0.2;   // nu
  int quadrature_order = 2;   // Gauss points per direction in each hexahedron

  // The Gauss order of an element with that many nodes (a Q1C2 Hex13 takes at least 3: its quadratic face).
  int order(int element_nodes) const { return element_nodes == 13 ? std::max(quadrature_order, 3) : quadrature_order; }

  static void declare(Teuchos::ParameterList& material);
  static SolidParameters from(const Teuchos::ParameterList& material);
};

// This rank's solid elements on the device (local node ids, global element ids, reference node positions).
struct SolidElements {
  DeviceView<int**> hex8_nodes, hex13_nodes;
  DeviceView<std::int64_t*> hex8_ids, hex13_ids;
  DeviceView<double* [3]> coordinates;
};

class SolidModel {
public:
  virtual ~SolidModel() = default;
  virtual std::string name() const = 0;
  // The elements' energy; their residual and (with the scatter's matrix) tangent scattered into the system; an
  // inverted element reported as its global id + 1 in `inverted` (atomic max), not assembled.
  virtual double assemble(const SolidElements& elements, const ElementScatter& scatter,
                          const DeviceView<std::int64_t[1]>& inverted) const = 0;
  // tr(sigma) of one element with `nodes` (8 or 13) reference positions X and displacements u: the mean over its
  // Gauss points (host).
  virtual double mean_cauchy_trace(const double (*X)[3], const double (*u)[3], int nodes) const = 0;
};

template <class Law>
class LawSolidModel : public SolidModel {
public:
  LawSolidModel(std::string name, Law law, const SolidParameters& parameters)
      : name_(std::move(name)), law_(law), parameters_(parameters)
  {
  }
  std::string name() const override { return name_; }

  double assemble(const SolidElements& elements, const ElementScatter& scatter,
                  const DeviceView<std::int64_t[1]>& inverted) const override
  {
    double energy = 0.0;
    energy += block<elements::Hex8Shape>("spatula: solid hex8 assembly", scatter, elements.hex8_nodes,
                                         elements.hex8_ids, elements.coordinates, inverted);
    energy += block<elements::Hex13Shape>("spatula: solid hex13 assembly", scatter, elements.hex13_nodes,
                                          elements.hex13_ids, elements.coordinates, inverted);
    return energy;
  }

  double mean_cauchy_trace(const double (*X)[3], const double (*u)[3], int nodes) const override
  {
    return nodes == 13 ? trace<elements::Hex13Shape>(X, u) : trace<elements::Hex8Shape>(X, u);
  }

private:
  template <class Shape>
  double block(const char* label, const ElementScatter& scatter, const DeviceView<int**>& nodes,
               const DeviceView<std::int64_t*>& ids, const DeviceView<double* [3]>& coordinates,
               const DeviceView<std::int64_t[1]>& inverted) const
  {
    double energy = 0.0;
    SolidKernel<Shape, Law> kernel{scatter, nodes, ids, coordinates, inverted, law_, parameters_.order(Shape::nodes)};
    Kokkos::parallel_reduce(label, Kokkos::RangePolicy<execution_space>(0, static_cast<int>(nodes.extent(0))),
                            kernel, energy);
    return energy;
  }
  template <class Shape>
  double trace(const double (*X)[3], const double (*u)[3]) const
  {
    double Xe[Shape::nodes][3], ue[Shape::nodes][3];
    for (int a = 0; a < Shape::nodes; ++a)
      for (int i = 0; i < 3; ++i) {
        Xe[a][i] = X[a][i];
        ue[a][i] = u[a][i];
      }
    return elements::mean_cauchy_trace<Shape>(law_, Xe, ue, parameters_.order(Shape::nodes));
  }

  std::string name_;
  Law law_;
  SolidParameters parameters_;
};

// The solid laws by name ('Material/law').
class SolidLawRegistry {
public:
  using Factory = std::function<std::shared_ptr<const SolidModel>(const SolidParameters&)>;
  static SolidLawRegistry& instance();
  void add(const std::string& name, Factory factory);
  std::vector<std::string> names() const;
  // The model of parameters.law (an InputError naming the key and the registered names if there is none).
  std::shared_ptr<const SolidModel> make(const SolidParameters& parameters) const;

private:
  SolidLawRegistry();
  std::map<std::string, Factory> factories_;
};

}  // namespace spatula::discretization
