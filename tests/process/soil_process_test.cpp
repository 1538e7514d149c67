// A robot set on soil starts at rest, seen on the bus as a user sees it:
// a real simpartner-sim (ttl=0) runs gen3 on a soil made here, LETE sand
// written out (Wong 2008, Table 2.3; not in the library), on each engine.
// From SIM_STATE's wheel_soil and bodies: every wheel's load within 2 % of
// its final one from 0.5 s on, the chassis slower than 1 mm/s from 1 s
// on, and each wheel's sinkage Bekker's at its own load within 2 % (the
// closed form of soil_closed_forms.h, apart from the sim's code).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "simpartner/channels.h"
#include "simpartner/control_t.hpp"
#include "simpartner/model_t.hpp"
#include "simpartner/state_t.hpp"
#include "simpartner/validate/soil_closed_forms.h"
#include "../support/bus_listener.h"
#include "../support/bus_url.h"
#include "../support/engines.h"
#include "../support/programs.h"
#include "../support/sim_process.h"
#include "../support/test_dir.h"

namespace simpartner {
namespace {

namespace fs = std::filesystem;

model::SoilParameters LeteSand() {
  model::SoilParameters p;
  p.n = 0.79;
  p.k_c = 102;
  p.k_phi = 5301;
  p.cohesion = 1.3;
  p.friction_angle = 31.1;
  p.shear_modulus = 0.01;
  p.unloading_stiffness = 0;
  p.unloading_growth = 503000;
  return p;
}

// gen3 (the shipped robot file) on a plane of LETE sand.
std::string WriteWorld(const fs::path& dir) {
  const fs::path world = dir / "gen3_on_lete_sand.xml";
  std::ofstream(world) << R"(<?xml version="1.0"?>
<world name="LeteSand" version="1">
  <gravity><x>0</x><y>-9.81</y><z>0</z></gravity>
  <surface material="lete_sand"><a>0</a><b>1</b><c>0</c><d>0</d></surface>
  <material name="lete_sand"><soil><n>0.79</n><kc>102</kc><kphi>5301</kphi>
    <cohesion>1.3</cohesion><frictionAngle>31.1</frictionAngle><shearModulus>0.01</shearModulus>
    <unloadingStiffness>0</unloadingStiffness><unloadingGrowth>503000</unloadingGrowth>
    <viscosity>0</viscosity></soil></material>
  <robot name="WorkPartner" file=")" << test_support::SourceDir()
                            << R"(/models/robots/workpartner_gen3.xml"/>
</world>)";
  return world.string();
}

// What the test follows: the model, and per state the wheels' loads and
// sinkages and the chassis' speed.
class Listener : public test_support::BusListener {
 public:
  explicit Listener(const std::string& url) : BusListener(url) {
    KeepLatest(channels::kModel, &model);
    Subscribe<state_t>(channels::kState, [this](const state_t& s) { OnState(s); });
  }
  int Body(const std::string& name) const {
    for (size_t k = 0; k < model.bodies.size(); ++k)
      if (model.bodies[k].name == name) return static_cast<int>(k);
    return -1;
  }

  model_t model{};
  struct Sample {
    double time = 0, chassis_speed = 0;
    std::map<int, double> load, sinkage;  // per wheel body
  };
  std::vector<Sample> samples;

 private:
  void OnState(const state_t& s) {
    if (model.simulation_id == 0 || s.simulation_id != model.simulation_id) return;
    Sample sample;
    sample.time = s.sim_time;
    for (const char* chassis : {"FrontChassis", "RearChassis"}) {
      const int b = Body(chassis);
      if (b < 0) continue;
      const double* v = s.bodies[static_cast<size_t>(b)].linear_velocity;
      sample.chassis_speed = std::max(sample.chassis_speed, std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
    }
    for (const wheel_soil_t& w : s.wheel_soil) {
      sample.load[w.body] = w.load;
      sample.sinkage[w.body] = w.sinkage;
    }
    samples.push_back(sample);
  }
};

class SoilProcessTest : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override { dir_ = test_support::FreshTestDir("sp_soil_process_"); }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  fs::path dir_;
};

TEST_P(SoilProcessTest, Gen3OnASoilMadeHereStandsAtRestAtBekkersSinkageFromStepZero) {
  const std::string url = test_support::BusUrl(0);
  Listener bus(url);
  test_support::SimProcess sim(WriteWorld(dir_), url, (dir_ / "sim.log").string(),
                               {test_support::EngineFlag(GetParam()), "--startPaused=1",
                                "--duration=1.5"});
  ASSERT_TRUE(bus.Until([&] { return bus.model.simulation_id != 0; }, 30)) << sim.Log();
  // Every state from step 0: run once the model is known.
  control_t resume{};
  resume.sender = "soil_process_test";
  resume.action = control_t::ACTION_RESUME;
  bus.Publish(channels::kControl, resume);
  ASSERT_TRUE(bus.Until([&] { return !bus.samples.empty() && bus.samples.back().time >= 1.5 - 1e-9; }, 60))
      << sim.Log();
  ASSERT_GT(bus.samples.size(), 1000u);  // of 1,500: a loaded machine may drop a few
  const Listener::Sample& last = bus.samples.back();
  ASSERT_EQ(last.load.size(), 4u);
  for (const Listener::Sample& s : bus.samples) {
    if (s.time >= 0.5) {
      for (const auto& [wheel, load] : last.load) {
        ASSERT_EQ(s.load.count(wheel), 1u) << "wheel " << wheel << " off the soil at " << s.time << " s";
        ASSERT_NEAR(s.load.at(wheel), load, 0.02 * load) << "wheel " << wheel << " at " << s.time << " s";
      }
    }
    if (s.time >= 1.0) {
      ASSERT_LT(s.chassis_speed, 1e-3) << "at " << s.time << " s";
    }
  }
  for (const auto& [wheel, load] : last.load) {
    const geometry_t& g = bus.model.bodies[static_cast<size_t>(wheel)].geometry;
    const double r = g.size[0], b = g.size[1];
    double lo = 0.0, hi = r / 2;
    for (int k = 0; k < 60; ++k)
      (validate::StandingLoad(LeteSand(), r, b, 0.5 * (lo + hi)) < load ? lo : hi) = 0.5 * (lo + hi);
    const double bekker = 0.5 * (lo + hi);
    EXPECT_NEAR(last.sinkage.at(wheel), bekker, 0.02 * bekker)
        << bus.model.bodies[static_cast<size_t>(wheel)].name << " at " << load << " N";
  }
}

INSTANTIATE_TEST_SUITE_P(Engines, SoilProcessTest, test_support::AllEngines(),
                         test_support::EngineTestName);

}  // namespace
}  // namespace simpartner
