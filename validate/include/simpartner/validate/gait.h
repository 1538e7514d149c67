// The gen1 gaits on ice (caterpillar, rolling walking): one run of a
// shipped gait sequence over whole cycles, the body's speed, and what each
// wheel does in each phase of the cycle (how far its centre moves, how
// much of that it rolls and how much it slides over the ground, and the
// ground's forces on it). The experiments and bench/gait_slip share it.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "simpartner/validate/experiment.h"
#include "simpartner/validate/plot.h"

namespace simpartner::validate {

inline constexpr int kGaitWheels = 4;  // Wheel1..4: front right, front left, rear left, rear right
inline constexpr double kGaitStart = 1.0;  // [s] the first cycle's start in the files

// One phase of a gait's cycle, as sequences/make_sequences.py writes it.
struct GaitPhase {
  double duration = 0.0;  // [s]
  std::string what;       // "leg 1 steps", "push"
  // The wheels the gait drives (a stepping foot's wheel rolls with it); the
  // others it holds (their axle motors keep their angle to the calf).
  std::array<bool, kGaitWheels> driven{};
};

struct GaitSequence {
  std::string file;         // under sequences/
  int cycles = 0;           // in the file
  std::vector<GaitPhase> phases;
  double stride = 0.0;      // [m] the body's advance per cycle with no slip
  double CycleTime() const;
};

// The shipped gaits (sequences/make_sequences.py caterpillar(), rolking()):
// the front feet reach, then the body follows over them (two phases); legs
// 1, 3, 2, 4 reach one at a time, then the body follows (five phases).
GaitSequence CaterpillarSequence();
GaitSequence RollingWalkingSequence();

// What one wheel does in one phase, per cycle (the mean over the cycles
// after the first). Distances are along the wheel's rolling direction
// (up x axle: forward), positive forward.
struct WheelInPhase {
  double moved = 0.0;       // [m] its centre's displacement
  double rolled = 0.0;      // [m] -r times its rotation (rolling without slip would move it this far)
  double slid = 0.0;        // [m] its contact point's displacement over the ground: moved - rolled
  double calf_rolled = 0.0; // [m] the part of `rolled` its calf's rotation gives (the whole of it when held)
  double friction = 0.0;    // [N] mean ground force along the rolling direction
  double load = 0.0;        // [N] mean ground force along up
};

struct PhaseSlip {
  GaitPhase phase;
  double body_moved = 0.0;  // [m] the rear chassis's displacement per cycle
  std::array<WheelInPhase, kGaitWheels> wheels{};
};

struct GaitRun {
  Series x;                 // rear chassis x against t
  double speed = 0.0;       // over the whole cycles after the first
  int cycles = 0;           // played
  double sim_seconds = 0.0;
  std::vector<PhaseSlip> phases;  // per cycle, over the cycles after the first
};

// Plays gait.file on slippery_ground.xml (all its cycles; three with
// context.quick) and measures. Throws simpartner::Error when the file does
// not last gait.cycles cycles of the phases' durations.
GaitRun RunGait(const Context& context, const GaitSequence& gait);

// A gen1 calf's pitch [rad] (from the ground's forward direction towards
// up) when its foot stands `foot` [m] ahead of its hip, the hip 0.48 m above
// the axle: the legs' geometry, as sequences/make_sequences.py foot_at()
// inverts it.
double CalfPitch(bool front, double foot);
// How far forward [m] a wheel held to its calf (its axle motor holding)
// rolls without slip while its foot moves from foot_from to foot_to ahead
// of its hip: the calf's pitch turns the wheel with it, r times the change.
double HeldWheelRoll(bool front, double foot_from, double foot_to);

// The phases' table in Markdown: per phase, the body's advance and each
// wheel's moved / rolled / slid [cm], and for the held wheels their
// friction against mu times their load.
std::string PhaseSlipTable(const std::vector<PhaseSlip>& phases, double mu);

}  // namespace simpartner::validate
