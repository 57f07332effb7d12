"""Observables of one frame, by subject: area fractions, rod order, rod layers, phases and the
condensate of an annulus. Every public name of the submodules is also here
(``analysis.classify_phase``)."""
from .area_fractions import (COUNTS, SPECIES, Profile, area_fraction_map, area_fraction_profile,
                             area_samples, default_spacing, global_area_fractions)
from .condensate import Arc, arc_drift, capping_rods, dense_arc, trap_spans
from .layers import (LayerSides, find_layers, fit_layer_exponential, interfacial_length, layer_drive,
                     layer_height_modes, layer_profile, layer_sides)
from .order import (alignment_of, gradient_alignment, nematic_order, polar_order, polarization, rod_environment,
                    smoothed_bead_field, tangential_polarization)
from .phases import (WINDOW, Phase, PhaseResult, PhaseThresholds, ShortRunWarning, SingleFrameWarning,
                     bead_mobility, classify_frames, classify_phase, decide_phase, iter_phases, layer_side_mobility,
                     majority_phase, phase_observables, rod_drift, segregation_index, window_observables,
                     window_of)
