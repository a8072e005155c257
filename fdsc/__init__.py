"""fdsc: a reproducible companion to *Frequency-dependent Switching Control for
Disturbance Attenuation of Linear Systems* (Zhang, Heiland, Benner, Du)."""

from .bands import PHI, Band, band_from_spec
from .exceptions import (
    BandError,
    DimensionError,
    FdscError,
    InfeasibleError,
    IterationLimitError,
    MemoryLimitError,
    SingularFrequencyError,
    SolverError,
    UnstableError,
    UnstableRunWarning,
    VerificationError,
)
from .frequency import BandPeak, band_peak, freqresp, sigma_max
from .plant import LTISystem, Plant, aircraft, paper_bands, paper_data, paper_gains

__version__ = "0.1.0"

__all__ = [
    "PHI", "Band", "band_from_spec",
    "FdscError", "BandError", "DimensionError", "SolverError", "InfeasibleError",
    "VerificationError", "IterationLimitError", "UnstableError", "SingularFrequencyError",
    "MemoryLimitError", "UnstableRunWarning",
    "BandPeak", "band_peak", "freqresp", "sigma_max",
    "LTISystem", "Plant", "aircraft", "paper_bands", "paper_data", "paper_gains",
]
