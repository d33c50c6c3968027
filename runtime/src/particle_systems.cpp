// X3D particle systems in the execution model (X3D 4.0 clause 40): each ParticleSystem
// met gets a particles::ParticleSimulation, seeded by the order the world met them (the
// same world gives the same particles on every machine) and started at the world's load
// time; every advanceTo() moves them to the clock's time (`--time T0:DT:N` steps by the
// fixed --time-step, so a sequence frames them exactly) and sends isActive on change.
// What they look like is the traversal's (scene/src/traversal_particles.cpp).
#include "execution_state.hpp"

namespace gs::runtime {

bool ExecutionModel::State::classifyParticleSystem(NodeState& ns) {
  if (ns.node->typeId() != vrml::NodeTypeId::ParticleSystem) return false;
  const std::uint64_t seed = 0x5eed0000ULL + particleSystems.size();
  ns.particles = std::make_unique<ParticleSystemState>(seed, model.now());
  ns.particles->isActive = ns.node->type().findExact("isActive");
  particleSystems.push_back(&ns);
  return true;
}

void ExecutionModel::State::evaluateParticleSystems() {
  const double now = model.now();
  for (NodeState* ns : particleSystems) {
    ParticleSystemState& p = *ns->particles;
    p.simulation.advance(*ns->node, now);
    if (p.simulation.clamped() && !p.reportedClamp) {
      p.reportedClamp = true;
      report(vrml::Severity::warning, *ns->node,
             "maxParticles above " + std::to_string(particles::kMaxParticles) +
                 ", or emitter or bounding geometry above " +
                 std::to_string(particles::kMaxTriangles) + " triangles, or more than " +
                 std::to_string(particles::kMaxTestsPerStep) +
                 " triangle tests in one step: limited");
    }
    if (p.isActive >= 0 && p.simulation.active() != p.sentActive) {
      p.sentActive = p.simulation.active();
      emitOwn(*ns, p.isActive, vrml::FieldValue::make<vrml::FieldType::SFBool>(p.sentActive));
    }
  }
}

const particles::ParticleSimulation* ExecutionModel::particleSimulation(
    const vrml::Node& node) const {
  const auto it = s_->nodes.find(&node);
  if (it == s_->nodes.end() || !it->second->particles) return nullptr;
  return &it->second->particles->simulation;
}

}  // namespace gs::runtime
