"""Bare-physics speed of a MuJoCo biped built like steplearn's humanoid (issue 16's yardstick).

The model copies the humanoid's default geometry and masses (`steplearn config`): a 9.15 kg
trunk and two 6-joint legs (hip yaw/roll/pitch, knee, ankle pitch/roll), 13.5 kg in all, 18 DoF
with the floating base, box feet on a plane with friction 0.8, PD position servos with the
default stiffness, damping and torque limits, and a 2 ms step. Its servos track an open-loop
stepping-in-place pattern (no controller, no estimator: bare physics), so the feet make and
break contact as in `examples/walk`. Prints the real-time factor on one core.

Run through `scripts/mujoco_baseline.sh`, which installs MuJoCo into a virtual environment.
"""

import argparse
import math
import time

import mujoco

# Defaults of `steplearn config` ([settings.sim.body]).
TORSO = dict(mass=9.153, length=0.576, com_height=0.360576, inertia=(0.747088, 0.747088, 0.15),
             depth=0.2, width=0.34)
THIGH = dict(length=0.49, mass=1.35, com=0.433, radius=0.06)
SHANK = dict(length=0.492, mass=0.62775, com=0.433, radius=0.045)
FOOT = dict(mass=0.19575, length=0.304, width=0.11, ankle_height=0.078, sole_offset_x=0.05)
HIP_HALF_WIDTH = 0.1
# (axis, limits, stiffness, damping, max torque) per leg joint, in the humanoid's order.
JOINTS = [
    ("0 0 1", (-0.6, 0.6), 300.0, 6.0, 60.0),  # hip yaw
    ("1 0 0", (-0.6, 0.6), 800.0, 15.0, 150.0),  # hip roll
    ("0 1 0", (-1.8, 0.8), 800.0, 15.0, 150.0),  # hip pitch
    ("0 1 0", (0.0, 2.4), 800.0, 15.0, 150.0),  # knee
    ("0 1 0", (-0.9, 0.9), 500.0, 8.0, 80.0),  # ankle pitch
    ("1 0 0", (-0.6, 0.6), 500.0, 8.0, 80.0),  # ankle roll
]
NAMES = ["hip_yaw", "hip_roll", "hip_pitch", "knee", "ankle_pitch", "ankle_roll"]
STEPS_PER_TICK = 5
INITIAL = [0.0, 0.0, -0.125, 0.25, -0.125, 0.0]


def joint(name, spec):
    axis, (lo, hi), _, damping, _ = spec
    return (f'<joint name="{name}" axis="{axis}" range="{lo} {hi}" limited="true" '
            f'damping="{damping}" armature="0.01"/>')


def leg(side, y):
    j = [joint(f"{side}_{n}", s) for n, s in zip(NAMES, JOINTS)]
    t, s, f = THIGH, SHANK, FOOT
    return f"""
    <body name="{side}_hip" pos="0 {y} 0">
      <inertial pos="0 0 0" mass="0.001" diaginertia="1e-6 1e-6 1e-6"/>
      {j[0]}
      <body name="{side}_hip_roll">
        <inertial pos="0 0 0" mass="0.001" diaginertia="1e-6 1e-6 1e-6"/>
        {j[1]}
        <body name="{side}_thigh">
          {j[2]}
          <inertial pos="0 0 {-t['com'] * t['length']}" mass="{t['mass']}"
                    diaginertia="0.0113 0.0113 0.0024"/>
          <geom type="capsule" fromto="0 0 0 0 0 {-t['length']}" size="{t['radius']}"/>
          <body name="{side}_shank" pos="0 0 {-t['length']}">
            {j[3]}
            <inertial pos="0 0 {-s['com'] * s['length']}" mass="{s['mass']}"
                      diaginertia="0.0055 0.0055 0.0006"/>
            <geom type="capsule" fromto="0 0 0 0 0 {-s['length']}" size="{s['radius']}"/>
            <body name="{side}_ankle" pos="0 0 {-s['length']}">
              <inertial pos="0 0 0" mass="0.001" diaginertia="1e-6 1e-6 1e-6"/>
              {j[4]}
              <body name="{side}_foot">
                {j[5]}
                <inertial pos="{f['sole_offset_x']} 0 {-f['ankle_height'] / 2}" mass="{f['mass']}"
                          diaginertia="0.0003 0.0016 0.0017"/>
                <geom type="box" pos="{f['sole_offset_x']} 0 {-f['ankle_height'] / 2}"
                      size="{f['length'] / 2} {f['width'] / 2} {f['ankle_height'] / 2}"/>
              </body>
            </body>
          </body>
        </body>
      </body>
    </body>"""


def model_xml():
    height = ((THIGH["length"] + SHANK["length"]) * math.cos(0.125) + FOOT["ankle_height"])
    tr = TORSO
    actuators = "\n".join(
        f'<position joint="{side}_{n}" kp="{kp}" forcerange="{-tau} {tau}" forcelimited="true"/>'
        for side in ("left", "right") for n, (_, _, kp, _, tau) in zip(NAMES, JOINTS))
    return f"""
<mujoco model="steplearn-biped">
  <option timestep="0.002" gravity="0 0 -9.81"/>
  <default><geom contype="2" conaffinity="1" friction="0.8 0.005 0.0001"/></default>
  <worldbody>
    <geom type="plane" size="20 20 0.1" contype="1" conaffinity="1"/>
    <body name="trunk" pos="0 0 {height + 0.002}">
      <freejoint/>
      <inertial pos="0 0 {tr['com_height']}" mass="{tr['mass']}"
                diaginertia="{tr['inertia'][0]} {tr['inertia'][1]} {tr['inertia'][2]}"/>
      <geom type="box" pos="0 0 {tr['length'] / 2}"
            size="{tr['depth'] / 2} {tr['width'] / 2} {tr['length'] / 2}"/>
      {leg("left", HIP_HALF_WIDTH)}
      {leg("right", -HIP_HALF_WIDTH)}
    </body>
  </worldbody>
  <actuator>
{actuators}
  </actuator>
</mujoco>"""


def targets(t, period):
    """Open-loop stepping in place: each leg lifts its foot in its half of the period."""
    out = []
    for side in range(2):
        phase = (t / period + 0.5 * side) % 1.0
        lift = math.sin(2.0 * math.pi * phase) if phase < 0.5 else 0.0
        sway = 0.04 * math.sin(2.0 * math.pi * t / period) * (1 if side == 0 else -1)
        q = list(INITIAL)
        q[1] += sway
        q[5] -= sway
        q[2] -= 0.25 * lift
        q[3] += 0.5 * lift
        q[4] -= 0.25 * lift
        out.extend(q)
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=120.0, help="simulated time (s)")
    parser.add_argument("--period", type=float, default=0.9, help="stepping period (s)")
    args = parser.parse_args()
    model = mujoco.MjModel.from_xml_string(model_xml())
    data = mujoco.MjData(model)
    for i, side in enumerate(("left", "right")):
        for n, q in zip(NAMES, INITIAL):
            data.joint(f"{side}_{n}").qpos = q
    mujoco.mj_forward(model, data)
    # New servo targets every control tick of 5 physics steps (10 ms), as in steplearn.
    ticks = int(round(args.seconds / (STEPS_PER_TICK * model.opt.timestep)))
    steps = ticks * STEPS_PER_TICK
    contacts = 0
    wall = 0.0  # time inside mj_step only: the Python that computes the targets is not counted
    for _ in range(ticks):
        data.ctrl[:] = targets(data.time, args.period)
        start = time.perf_counter()
        mujoco.mj_step(model, data, nstep=STEPS_PER_TICK)
        wall += time.perf_counter() - start
        contacts += data.ncon
    mass = sum(model.body_mass)
    print(f"mujoco {mujoco.__version__}: {model.nv} DoF, {mass:.2f} kg, dt {model.opt.timestep} s; "
          f"trunk height at the end {data.qpos[2]:.2f} m, {contacts / ticks:.1f} contacts per tick")
    print(f"{args.seconds:.0f} s simulated in {wall:.2f} s wall: {args.seconds / wall:.0f}x real time")


if __name__ == "__main__":
    main()
