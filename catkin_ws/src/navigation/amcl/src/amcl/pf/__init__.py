"""Particle filter with KLD-sampling and recovery (amcl's pf/)."""
from .pf import ParticleFilter, Cluster, resample_limit, resample_limits, histogram_bins  # noqa: F401
