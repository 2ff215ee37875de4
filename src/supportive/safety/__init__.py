"""Keeping a novice safe (§3.5): action priors, P(safe | τ), expected damage and the caregiver's policy."""

from supportive.safety.caregiver import Caregiver, Decision, Intervention
from supportive.safety.danger import DangerModel, Hazard
from supportive.safety.episode import EPISODE_STEPS, THRESHOLD, EpisodeResult, Frame, map_model, run_episode
from supportive.safety.priors import ActionPriors, expert_trajectory
from supportive.safety.safe_probability import SafetyEstimate

__all__ = [
    "EPISODE_STEPS",
    "THRESHOLD",
    "ActionPriors",
    "Caregiver",
    "DangerModel",
    "Decision",
    "EpisodeResult",
    "Frame",
    "Hazard",
    "Intervention",
    "SafetyEstimate",
    "expert_trajectory",
    "map_model",
    "run_episode",
]
