"""Particle weights: gmapping's normalisation, Neff and low-variance resampling."""
import numpy as np


def normalize_log_weights(log_weights, obs_gain):
    """gmapping's normalize(): w_i ∝ exp((l_i - max l) / (ogain * N)); returns weights summing to 1."""
    lw = np.asarray(log_weights, dtype=np.float64)
    gain = 1.0 / (obs_gain * len(lw))
    w = np.exp(gain * (lw - lw.max()))
    return w / w.sum()


def neff(weights):
    """Effective sample size 1 / sum(w^2) of normalised weights."""
    return 1.0 / float(np.sum(np.square(weights)))


def low_variance_indices(weights, rng):
    """Systematic (low-variance) resampling: N indices drawn in proportion to the weights."""
    n = len(weights)
    positions = (rng.random() + np.arange(n)) / n
    cum = np.cumsum(weights)
    cum[-1] = 1.0
    return np.searchsorted(cum, positions, side='left')


def entropy(weights):
    """Entropy of the normalised weights (slam_gmapping's ~entropy)."""
    w = np.asarray(weights, dtype=np.float64)
    w = w[w > 0.0]
    return float(-np.sum(w * np.log(w)))
