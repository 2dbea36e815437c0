"""Automatic graph selection and initialisation (the MATch paper, section 4.2), a library beneath
the pipeline: it ranks the library graphs for a photo (``rank``), proposes starting parameters
from per-graph models (``predictor``, ``bank``, ``start``) and fits the best-ranked candidates
under one shared budget (``fit``). The caller decides how many candidates (``k``) and with which
optimiser ``Schedule``; nothing here knows quality names or result folders."""
from .descriptor import shared_vgg
from .fit import Fitted, budget_factor, frame_start, select_and_fit
from .rank import NoSelectionModels, available_models, check_photo, rank_graphs
from .start import choose_start

__all__ = ["Fitted", "NoSelectionModels", "available_models", "budget_factor", "check_photo", "choose_start",
           "frame_start", "rank_graphs", "select_and_fit", "shared_vgg"]
