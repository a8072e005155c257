"""fdsc: frequency-dependent switching control (FDSC) for disturbance attenuation of linear systems.

A library for any plant and any frequency ranges, after Zhang, Heiland, Benner and Du,
*Frequency-dependent Switching Control for Disturbance Attenuation of Linear Systems*: bands and
Ψ, band peaks of σ_max, Lemma 1 (the generalized KYP lemma), band-limited and H∞ state-feedback
synthesis, the FD-EEF/FD-EPF, Theorem 1's LMIs (the law's Q's designed, or the least γ's for
given ones), an exact simulator for switched loops, and the :class:`FDSC` design object. The
paper's reproduction lives in the separate layer :mod:`fdsc.paper`, which this package never
imports.

Docstrings cite the paper as "paper eq. (N)" with the numbering of the compiled paper: the system
is paper eq. (6), the LMI of Lemma 1 paper eq. (7), the plant paper eq. (10), the FD-EEF and
FD-EPF paper eqs. (19)-(20) and (28)-(29), the switching law paper eq. (31) and Theorem 1 paper
eqs. (33)-(34). Frequencies are in rad/s, times in s.
"""

import importlib
import sys
import types
from typing import TYPE_CHECKING

#: Where each public name lives. The submodules are imported on first use (PEP 562), so that a
#: program that only simulates does not load CVXPY and its solvers (``import fdsc`` alone loads
#: NumPy only; ``fdsc.simulate_stream`` loads SciPy and numba, ``fdsc.synthesize`` CVXPY).
_EXPORTS = {
    "bands": ("PHI", "Band", "band_from_spec"),
    "controller": ("Controller", "as_controller", "switched_loops"),
    "weighted": ("WeightedDesign", "DynamicFront", "band_weight", "weighted_hinf", "dynamic_front"),
    "h2": ("shaping_filter", "fit_shaping_filter", "h2_controller"),
    "class_spectrum": ("SegmentClass",),
    "optimal_lti": ("OptimalLTI", "expected_power", "feedforward_basis", "optimal_lti", "wiener_power"),
    "tuning": ("TuneResult", "loop_energy", "tune_controller"),
    "noncausal": ("LQData", "NoncausalLimit", "lq_data", "noncausal_limit", "tone_limit"),
    "predictive": ("PredictiveLaw", "PredictiveRun", "ToneEstimate", "identify_tones"),
    "design": ("FDSC",),
    "dwell": ("DwellCheck", "DwellTimeBound", "LyapunovDwell", "PeriodicDwellMargin",
              "check_dwell_bound", "dwell_time_bound", "lyapunov_dwell", "periodic_dwell_margin",
              "random_dwell_signal", "switched_states"),
    "energy": ("PowerSplit", "average_power", "fdeef", "fdeef_autonomous", "fdeef_parseval_autonomous",
               "instantaneous_power", "steady_state_power"),
    "exceptions": ("BandError", "DimensionError", "EnergyOverflowError", "EnergyUnderflowWarning",
                   "FdscError", "InfeasibleError", "IterationLimitError", "MemoryLimitError",
                   "SingularFrequencyError", "SolverError", "UnstableError", "UnstableRunWarning",
                   "VerificationError", "ResolutionWarning"),
    "frequency": ("BandPeak", "band_peak", "freqresp", "sigma_max", "steady_state_gain", "steady_state_gains",
                  "steady_state_gains"),
    "lmi": ("GKYPResult", "gkyp_certify", "gkyp_gamma"),
    "multiband": ("FrontPoint", "MultibandResult", "ParetoFront", "dominating_gain", "pareto_front",
                  "synthesize_multiband"),
    "lyapunov_jumps": ("SwitchingCertificate", "certify_switching", "certify_switching_gain",
                       "switching_forms"),
    "plant": ("LTISystem", "Plant", "as_plant", "as_system"),
    "random_systems": ("random_hurwitz", "random_plant", "random_spd", "random_system"),
    "rules": ("PRINTED", "SwitchRule"),
    "scores": ("frequency_weight", "law_weight", "score_average", "score_matrix"),
    "signals": ("LocalizedDominance", "Piecewise", "Sampled", "Sinusoids", "dominance_degree",
                "localized_dominance"),
    "simulate": ("SimResult", "envelope", "simulate", "time_grid"),
    "stream": ("BatchResult", "Case", "StreamResult", "Trace", "simulate_batch", "simulate_stream"),
    "supervisor": ("LAWS", "Supervisor", "supervise"),
    "prepared": ("Prepared", "shift_signal"),
    "decisions": ("SupervisedRun",),
    "law_certificate": ("LawCertificate", "copies_l2_bound"),
    "realization": ("band_filter", "lqr_gain"),
    "gc_dwell": ("DwellCertificate", "geromel_colaneri_dwell"),
    "min_switching": ("MinSwitchingCertificate", "min_switching"),
    "supervise_batch": ("SupervisedCase", "supervise_batch"),
    "switching": ("Theorem1Result", "certify_q", "design_q"),
    "synthesis": ("SynthesisResult", "optimize_gain", "synthesize", "synthesize_hinf"),
    "three_mode": ("ScoreCertificate", "certify_scores", "design_scores"),
}
_WHERE = {name: module for module, names in _EXPORTS.items() for name in names}


def __getattr__(name):
    """Import the submodule that defines ``name`` (or the submodule ``name``) on first use."""
    module = _WHERE.get(name)
    if module is not None:
        value = getattr(importlib.import_module(f".{module}", __name__), name)
        globals()[name] = value
        return value
    try:
        return importlib.import_module(f".{name}", __name__)
    except ModuleNotFoundError as err:
        if err.name != f"{__name__}.{name}":
            raise
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}") from None


def __dir__():
    return sorted(set(globals()) | set(_WHERE))


class _Package(types.ModuleType):
    """The package's module type: importing the submodule ``fdsc.simulate`` must not replace the
    function ``fdsc.simulate`` (the import system sets a package attribute for every submodule
    it loads; with eager imports the function was bound afterwards, with lazy ones it is not)."""

    def __setattr__(self, name, value):
        if name in _WHERE and isinstance(value, types.ModuleType):
            return
        super().__setattr__(name, value)


sys.modules[__name__].__class__ = _Package


if TYPE_CHECKING:  # what the lazy names are, for type checkers and editors
    from .bands import PHI, Band, band_from_spec
    from .class_spectrum import SegmentClass
    from .controller import Controller, as_controller, switched_loops
    from .decisions import SupervisedRun
    from .design import FDSC
    from .dwell import (
        DwellCheck,
        DwellTimeBound,
        LyapunovDwell,
        PeriodicDwellMargin,
        check_dwell_bound,
        dwell_time_bound,
        lyapunov_dwell,
        periodic_dwell_margin,
        random_dwell_signal,
        switched_states,
    )
    from .energy import (
        PowerSplit,
        average_power,
        fdeef,
        fdeef_autonomous,
        fdeef_parseval_autonomous,
        instantaneous_power,
        steady_state_power,
    )
    from .exceptions import (
        BandError,
        DimensionError,
        EnergyOverflowError,
        EnergyUnderflowWarning,
        FdscError,
        InfeasibleError,
        IterationLimitError,
        MemoryLimitError,
        ResolutionWarning,
        SingularFrequencyError,
        SolverError,
        UnstableError,
        UnstableRunWarning,
        VerificationError,
    )
    from .frequency import BandPeak, band_peak, freqresp, sigma_max, steady_state_gain, steady_state_gains
    from .gc_dwell import DwellCertificate, geromel_colaneri_dwell
    from .h2 import fit_shaping_filter, h2_controller, shaping_filter
    from .law_certificate import LawCertificate, copies_l2_bound
    from .lmi import GKYPResult, gkyp_certify, gkyp_gamma
    from .lyapunov_jumps import (
        SwitchingCertificate,
        certify_switching,
        certify_switching_gain,
        switching_forms,
    )
    from .min_switching import MinSwitchingCertificate, min_switching
    from .multiband import (
        FrontPoint,
        MultibandResult,
        ParetoFront,
        dominating_gain,
        pareto_front,
        synthesize_multiband,
    )
    from .noncausal import LQData, NoncausalLimit, lq_data, noncausal_limit, tone_limit
    from .optimal_lti import OptimalLTI, expected_power, feedforward_basis, optimal_lti, wiener_power
    from .plant import LTISystem, Plant, as_plant, as_system
    from .predictive import PredictiveLaw, PredictiveRun, ToneEstimate, identify_tones
    from .prepared import Prepared, shift_signal
    from .random_systems import random_hurwitz, random_plant, random_spd, random_system
    from .realization import band_filter, lqr_gain
    from .rules import PRINTED, SwitchRule
    from .scores import frequency_weight, law_weight, score_average, score_matrix
    from .signals import (
        LocalizedDominance,
        Piecewise,
        Sampled,
        Sinusoids,
        dominance_degree,
        localized_dominance,
    )
    from .simulate import SimResult, envelope, simulate, time_grid
    from .stream import BatchResult, Case, StreamResult, Trace, simulate_batch, simulate_stream
    from .supervise_batch import SupervisedCase, supervise_batch
    from .supervisor import LAWS, Supervisor, supervise
    from .switching import Theorem1Result, certify_q, design_q
    from .synthesis import SynthesisResult, optimize_gain, synthesize, synthesize_hinf
    from .three_mode import ScoreCertificate, certify_scores, design_scores
    from .tuning import TuneResult, loop_energy, tune_controller
    from .weighted import DynamicFront, WeightedDesign, band_weight, dynamic_front, weighted_hinf

__version__ = "0.2.0"

__all__ = [
    # frequency ranges
    "PHI", "Band", "band_from_spec",
    # systems and controllers
    "LTISystem", "Plant", "as_system", "as_plant", "Controller", "as_controller", "switched_loops",
    # frequency responses and Lemma 1
    "BandPeak", "band_peak", "freqresp", "sigma_max", "steady_state_gain", "steady_state_gains",
    "GKYPResult", "gkyp_gamma", "gkyp_certify",
    # synthesis
    "SynthesisResult", "synthesize", "synthesize_hinf", "optimize_gain",
    "MultibandResult", "synthesize_multiband", "FrontPoint", "ParetoFront", "pareto_front",
    "dominating_gain",
    # fixed controllers for a disturbance class: weighted H∞, H2 for a spectrum, tuned on draws
    "WeightedDesign", "DynamicFront", "band_weight", "weighted_hinf", "dynamic_front",
    "shaping_filter", "fit_shaping_filter", "h2_controller", "TuneResult", "loop_energy",
    "tune_controller",
    # what any controller can do on a draw, the optimal LTI controller of a class, and a law that
    # predicts the disturbance
    "LQData", "lq_data", "NoncausalLimit", "noncausal_limit", "tone_limit", "SegmentClass",
    "OptimalLTI", "optimal_lti", "expected_power", "wiener_power", "feedforward_basis", "ToneEstimate",
    "identify_tones", "PredictiveRun", "PredictiveLaw",
    # a switching law on the disturbance estimate
    "Supervisor", "Prepared", "SupervisedRun", "supervise", "LAWS", "band_filter", "lqr_gain",
    "shift_signal", "DwellCertificate", "geromel_colaneri_dwell", "MinSwitchingCertificate",
    "min_switching", "SupervisedCase", "supervise_batch", "LawCertificate", "copies_l2_bound",
    # FD-EEF / FD-EPF
    "PowerSplit", "instantaneous_power", "fdeef", "average_power", "steady_state_power",
    "fdeef_autonomous", "fdeef_parseval_autonomous",
    # Theorem 1 and the FDSC design
    "Theorem1Result", "certify_q", "design_q", "FDSC",
    # signals and simulation
    "Sinusoids", "Piecewise", "Sampled", "dominance_degree", "localized_dominance",
    "LocalizedDominance", "SimResult", "simulate", "time_grid", "envelope",
    "SwitchRule", "PRINTED",
    # gap-closing certificates of the switching law
    "SwitchingCertificate", "certify_switching", "certify_switching_gain", "switching_forms",
    # dwell-time certificates
    "DwellTimeBound", "dwell_time_bound", "LyapunovDwell", "lyapunov_dwell", "PeriodicDwellMargin",
    "periodic_dwell_margin", "DwellCheck", "check_dwell_bound", "random_dwell_signal", "switched_states",
    # second-order scores and their certificate (three modes)
    "score_matrix", "law_weight", "frequency_weight", "score_average", "ScoreCertificate",
    "certify_scores", "design_scores",
    "Case", "Trace", "StreamResult", "BatchResult", "simulate_stream", "simulate_batch",
    # seeded random systems
    "random_hurwitz", "random_system", "random_plant", "random_spd",
    # exceptions
    "FdscError", "BandError", "DimensionError", "SolverError", "InfeasibleError",
    "VerificationError", "IterationLimitError", "UnstableError", "SingularFrequencyError",
    "MemoryLimitError", "EnergyOverflowError", "EnergyUnderflowWarning", "UnstableRunWarning",
    "ResolutionWarning",
]
