#include "simpartner/validate/soil_rig.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "simpartner/model/soil_library.h"
#include "simpartner/text.h"
#include "simpartner/validate/sim_run.h"

namespace simpartner::validate {
namespace {

std::string Number(double v) { return ShortestNumber(v); }

std::string At(double x, double y) {
  return "<transformation><T00>1</T00><T01>0</T01><T02>0</T02><T03>" + Number(x) +
         "</T03><T10>0</T10><T11>1</T11><T12>0</T12><T13>" + Number(y) +
         "</T13><T20>0</T20><T21>0</T21><T22>1</T22><T23>0</T23></transformation>";
}

std::string Vector(const char* tag, double x, double y, double z) {
  return std::string("<") + tag + "><x>" + Number(x) + "</x><y>" + Number(y) + "</y><z>" +
         Number(z) + "</z></" + tag + ">";
}

// The gravity, the surface of soil and its material.
std::string Ground(const RigSoil& soil) {
  return Vector("gravity", 0, -kRigGravity, 0) +
         R"(<surface material="soil"><a>0</a><b>1</b><c>0</c><d>0</d></surface>
  <material name="soil"><mu>0.5</mu><soil library=")" +
         model::kShippedSoilLibrary + "\" name=\"" + soil.name + "\">" + soil.overrides +
         "</soil></material>\n";
}

std::string Wheel(const std::string& name, double mass, double x, double radius = kRigRadius,
                  double width = kRigWidth) {
  return "<object type=\"Cylinder\" name=\"" + name + "\"><mass>" + Number(mass) +
         "</mass><radius>" + Number(radius) + "</radius><length>" + Number(width) + "</length>" +
         At(x, radius) + "</object>\n";
}

std::string StandingWorld(const RigSoil& soil, double mass) {
  return "<world name=\"SoilStandingWheel\">" + Ground(soil) + Wheel("Wheel", mass, 0) + "</world>";
}

// Carrier and wheel number k, x metres along the rail, hung from the sled.
std::string RigWheel(int k, double x, const RigSetup& setup) {
  const std::string n = std::to_string(k);
  const double r = setup.radius;
  return "<object type=\"Box\" name=\"Carrier" + n + "\"><mass>" +
         Number(setup.load / kRigGravity - setup.wheel_mass) + "</mass>" +
         Vector("size", 0.05, 0.05, 0.05) + At(x, r) + "</object>\n" +
         Wheel("Wheel" + n, setup.wheel_mass, x, r, setup.width) +
         "<joint type=\"Slider\" name=\"Hanger" + n + "\"><body1>Carrier" + n +
         "</body1><body2>Sled</body2>" + Vector("axis1", 0, 1, 0) + "</joint>\n" +
         "<joint type=\"Hinge\" name=\"Axle" + n + "\"><body1>Carrier" + n +
         "</body1><body2>Wheel" + n + "</body2>" + Vector("anchor", x, r, 0) +
         Vector("axis1", 0, 0, 1) + "</joint>\n";
}

std::string RigWorld(const RigSetup& setup) {
  std::string xml = "<world name=\"SoilRig\">" + Ground(setup.soil) +
                    "<object type=\"Box\" name=\"Sled\"><mass>5</mass>" +
                    Vector("size", 0.2, 0.1, 0.2) + At(0, 1.5) + "</object>\n" +
                    "<joint type=\"Slider\" name=\"Rail\"><body1>Sled</body1><body2>world</body2>" +
                    Vector("axis1", 1, 0, 0) + "</joint>\n" + RigWheel(1, 0, setup);
  if (setup.tandem) xml += RigWheel(2, -setup.spacing, setup);
  return xml + "</world>";
}

// Loads a rig's world; null (with the engine's reason) when the engine
// cannot model it.
std::unique_ptr<SimRun> Load(const Context& context, const std::string& name,
                             const std::string& xml, double stepsize, std::string* not_applicable) {
  model::World world = LoadWorldText(context, name, xml);
  Parameters params = context.params;
  params.stepsize = stepsize;
  *not_applicable = EngineLacks(world, params);
  if (!not_applicable->empty()) return nullptr;
  return std::make_unique<SimRun>(context, name, std::move(world), params);
}

}  // namespace

StandingRun RunStandingWheel(const Context& context, const RigSoil& soil, double mass,
                             double stepsize, std::string* not_applicable) {
  StandingRun out;
  const auto run =
      Load(context, "soil_standing_wheel.xml", StandingWorld(soil, mass), stepsize, not_applicable);
  if (run == nullptr) return out;
  const int wheel = run->Body("Wheel");
  const int64_t ramp = run->StepAt(2.0);
  // A support force for the coming step: the weight, falling to 0 over the ramp.
  auto support = [&] {
    const double share = 1.0 - std::min(1.0, static_cast<double>(run->sim().step()) / ramp);
    run->sim().engine().AddForce(wheel, Eigen::Vector3d(0, mass * kRigGravity * share, 0));
  };
  support();
  run->RunUntil(3.0, support);
  const Eigen::Vector3d at = run->Position(wheel);
  out.sinkage = kRigRadius - at.y();
  out.drift = std::hypot(at.x(), at.z());
  out.sim_seconds = run->time();
  return out;
}

RigRun RunRig(const Context& context, const RigSetup& setup, std::string* not_applicable) {
  RigRun out;
  const auto run = Load(context, "soil_rig.xml", RigWorld(setup), setup.stepsize, not_applicable);
  if (run == nullptr) return out;
  const int wheels = setup.tandem ? 2 : 1;
  const int rail = run->Joint("Rail");
  int carrier[2] = {0, 0}, wheel[2] = {0, 0}, axle[2] = {0, 0};
  for (int k = 0; k < wheels; ++k) {
    const std::string n = std::to_string(k + 1);
    carrier[k] = run->Body("Carrier" + n);
    wheel[k] = run->Body("Wheel" + n);
    axle[k] = run->Joint("Axle" + n);
  }
  const int64_t lowered = run->StepAt(1.0);
  const int64_t averaged_from = run->StepAt(setup.drive_seconds);  // the last second
  const double omega = setup.slip >= 0 ? setup.speed / ((1 - setup.slip) * setup.radius)
                                       : (1 + setup.slip) * setup.speed / setup.radius;
  int64_t counted = 0;
  // The commands of the coming step: lowering (a support falling from the
  // weight to 0 over the first second), then the drive. robot.dtd: a
  // positive rate of body2 (the wheel) about the axle rolls toward +x.
  auto command = [&] {
    const int64_t step = run->sim().step();
    const bool driving = step >= lowered;
    const double share = driving ? 0.0 : 1.0 - static_cast<double>(step) / lowered;
    run->sim().engine().SetMotor(rail, 0, driving ? setup.speed : 0.0, 1e5);
    for (int k = 0; k < wheels; ++k) {
      run->sim().engine().AddForce(carrier[k], Eigen::Vector3d(0, setup.load * share, 0));
      const bool spun = setup.driven || !driving;  // towed: the axle free once moving
      run->sim().engine().SetMotor(axle[k], 0, driving && setup.driven ? omega : 0.0,
                                   spun ? 1e5 : 0.0);
    }
  };
  command();
  run->RunUntil(1.0 + setup.drive_seconds, [&] {
    if (run->sim().step() > averaged_from) {
      for (int k = 0; k < wheels; ++k) out.sinkage[k] += setup.radius - run->Position(wheel[k]).y();
      // The rail holds the sled back: its force on the sled is minus the pull.
      out.pull -= run->sim().engine().ReadJoint(rail).force1.x();
      ++counted;
    }
    command();
  });
  for (double& s : out.sinkage) s /= static_cast<double>(counted);
  out.pull /= static_cast<double>(counted);
  out.sim_seconds = run->time();
  return out;
}

}  // namespace simpartner::validate
