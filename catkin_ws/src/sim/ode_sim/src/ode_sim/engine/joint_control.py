"""The maths of the ros_control bridge (DefaultRobotHWSim's writeSim/readSim on the engine's
joints): interfaces, limits, control_toolbox's PID, hinge unwrapping, and apply_commands(), which
turns each joint's command into an effort, a motor velocity or a position target. No ROS."""
import math

EFFORT = 'EffortJointInterface'
VELOCITY = 'VelocityJointInterface'
POSITION = 'PositionJointInterface'
STATE = 'JointStateInterface'
COMMAND_INTERFACES = (EFFORT, VELOCITY, POSITION)


def bare_interface(name):
    return name.strip().rsplit('/', 1)[-1]


def clamp(v, lo, hi):
    if lo is not None and v < lo:
        return lo
    if hi is not None and v > hi:
        return hi
    return v


def shortest_angular_distance(a, b):
    """b - a wrapped to [-pi, pi]."""
    d = math.fmod(b - a + math.pi, 2 * math.pi)
    if d < 0:
        d += 2 * math.pi
    return d - math.pi


class Pid:
    """control_toolbox::Pid as used by DefaultRobotHWSim: p, i, d, i_clamp (the integral term
    is limited to [-|i_clamp|, |i_clamp|]; i_clamp_min / i_clamp_max override), d on the error."""

    def __init__(self, p, i=0.0, d=0.0, i_clamp=0.0, i_clamp_min=None, i_clamp_max=None):
        self.p, self.i, self.d = float(p), float(i), float(d)
        self.i_max = abs(float(i_clamp)) if i_clamp_max is None else abs(float(i_clamp_max))
        self.i_min = -abs(float(i_clamp)) if i_clamp_min is None else -abs(float(i_clamp_min))
        self.reset()

    def reset(self):
        self.i_error = 0.0
        self.last_error = 0.0

    def compute(self, error, dt):
        if dt <= 0 or not math.isfinite(error):
            return 0.0
        self.i_error += dt * error
        i_term = clamp(self.i * self.i_error, self.i_min, self.i_max)
        d_term = self.d * (error - self.last_error) / dt
        self.last_error = error
        return self.p * error + i_term + d_term


class BridgeJoint:
    """One transmission joint: the sim joint, its interface, limits, PID and command."""

    def __init__(self, joint, interface, reduction):
        self.name = joint.name
        self.joint = joint
        self.interface = interface          # one of COMMAND_INTERFACES, or STATE
        self.reduction = reduction
        d = joint.desc
        limited = joint.type in ('revolute', 'prismatic')
        self.lower = d.lower if limited and d.lower is not None and d.upper is not None \
            and d.upper >= d.lower else None
        self.upper = d.upper if self.lower is not None else None
        self.effort = joint.limit_effort
        self.velocity = joint.limit_velocity
        self.pid = None
        self.command = 0.0
        self.hold = None                    # position held while the e-stop is active
        self.wraps = joint.hinge            # ODE reports hinge angles in [-pi, pi]
        self._pos = None

    def position(self):
        """The joint position, hinge angles unwrapped (as DefaultRobotHWSim::readSim); call
        at least once per step so that no turn is missed."""
        if not self.wraps:
            self._pos = self.joint.position()
            return self._pos
        raw = self.joint.joint.getAngle()       # a hinge: SimJoint.position() without the test
        if self._pos is None:
            self._pos = raw
        else:
            self._pos += shortest_angular_distance(self._pos, raw)
        return self._pos

    def description(self):
        """The entry of NS/ode_sim/joints (limits only where the URDF has them)."""
        out = {'name': self.name, 'interface': self.interface, 'reduction': float(self.reduction)}
        if self.lower is not None:
            out['lower'] = float(self.lower)
            out['upper'] = float(self.upper)
        if self.effort is not None:
            out['effort'] = float(self.effort)
        if self.velocity is not None:
            out['velocity'] = float(self.velocity)
        return out


def neg(v):
    return None if v is None else -v


def apply_commands(joints, estop, dt):
    """Write the commands of BridgeJoints to their joints (every physics step, as writeSim);
    with the e-stop on, efforts and velocities are zero and positions hold where they were."""
    for j in joints:
        iface = j.interface
        if iface == STATE:
            j.position()
            continue
        sj = j.joint
        q = j.position()
        if estop:
            if j.hold is None:
                j.hold = q
        else:
            j.hold = None
        cmd = j.command
        if iface == EFFORT:
            sj.set_effort(0.0 if estop else clamp(cmd, neg(j.effort), j.effort))
        elif iface == VELOCITY:
            v = 0.0 if estop else clamp(cmd, neg(j.velocity), j.velocity)
            if j.pid is not None:
                effort = j.pid.compute(v - sj.velocity(), dt)
                sj.set_effort(clamp(effort, neg(j.effort), j.effort))
            else:
                sj.set_velocity(v, fmax=j.effort)
        else:
            p = j.hold if estop else clamp(cmd, j.lower, j.upper)
            if j.pid is not None:
                if sj.type == 'continuous':
                    err = shortest_angular_distance(q, p)
                else:
                    err = p - q
                effort = j.pid.compute(err, dt)
                sj.set_effort(clamp(effort, neg(j.effort), j.effort))
            else:
                # the motor servoes the raw (wrapped) angle: aim at the same offset
                sj.set_position_target(sj.position() + (p - q))
