"""slam_gmapping's parameters with the original's defaults (slam_gmapping.cpp, Noetic 1.4.2)."""
from dataclasses import dataclass, fields


@dataclass
class SlamParams:
    particles: int = 30
    delta: float = 0.05
    xmin: float = -100.0
    ymin: float = -100.0
    xmax: float = 100.0
    ymax: float = 100.0
    maxRange: float = -1.0          # <= 0: scan.range_max - 0.01 (from the first scan)
    maxUrange: float = -1.0         # <= 0: = maxRange
    map_update_interval: float = 5.0
    linearUpdate: float = 1.0
    angularUpdate: float = 0.5
    temporalUpdate: float = -1.0
    sigma: float = 0.05
    kernelSize: int = 1
    lstep: float = 0.05
    astep: float = 0.05
    iterations: int = 5
    lsigma: float = 0.075
    ogain: float = 3.0
    lskip: int = 0
    minimumScore: float = 0.0
    srr: float = 0.1
    srt: float = 0.2
    str: float = 0.1
    stt: float = 0.2
    resampleThreshold: float = 0.5
    occ_thresh: float = 0.25
    llsamplerange: float = 0.01
    llsamplestep: float = 0.01
    lasamplerange: float = 0.005
    lasamplestep: float = 0.005
    throttle_scans: int = 1
    base_frame: str = 'base_link'
    map_frame: str = 'map'
    odom_frame: str = 'odom'
    transform_publish_period: float = 0.05
    tf_delay: float = -1.0          # < 0: = transform_publish_period

    @classmethod
    def names(cls):
        return [f.name for f in fields(cls)]


class ParamError(ValueError):
    """A parameter value slam_gmapping cannot use; str(e) names the parameter."""


def validate(p):
    """Raise ParamError for values the filter cannot run with."""
    if p.particles < 1:
        raise ParamError('~particles must be >= 1 (got %d)' % p.particles)
    if not p.delta > 0.0:
        raise ParamError('~delta must be > 0 m (got %g)' % p.delta)
    if not (p.xmin < p.xmax and p.ymin < p.ymax):
        raise ParamError('~xmin/~xmax/~ymin/~ymax must give xmin < xmax and ymin < ymax (got %g %g %g %g)'
                         % (p.xmin, p.xmax, p.ymin, p.ymax))
    for name in ('sigma', 'lsigma', 'ogain', 'lstep', 'astep'):
        if not getattr(p, name) > 0.0:
            raise ParamError('~%s must be > 0 (got %g)' % (name, getattr(p, name)))
    for name in ('kernelSize', 'lskip', 'iterations'):
        if getattr(p, name) < 0:
            raise ParamError('~%s must be >= 0 (got %d)' % (name, getattr(p, name)))
    if p.throttle_scans < 1:
        raise ParamError('~throttle_scans must be >= 1 (got %d)' % p.throttle_scans)
    if not 0.0 <= p.occ_thresh <= 1.0:
        raise ParamError('~occ_thresh must be in [0, 1] (got %g)' % p.occ_thresh)
