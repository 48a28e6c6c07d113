"""Navigation: stage-1 A* on the home's grid, topological map, localisation, local controllers."""

from homebot.navigation.astar import astar
from homebot.navigation.dwa import DynamicWindowPlanner
from homebot.navigation.likelihood import LikelihoodField
from homebot.navigation.local_planner import MotionSearchPlanner
from homebot.navigation.localisation import MclParameters, MonteCarloLocalisation
from homebot.navigation.localmap import LocalController, LocalGrid
from homebot.navigation.navigate import (
    NavigateToPose,
    NavigationFeedback,
    NavigationGoal,
    NavigationResult,
    OdometryPose,
    StopReason,
)
from homebot.navigation.navigator import Navigator
from homebot.navigation.topology import TopologicalMap

__all__ = ["DynamicWindowPlanner", "LikelihoodField", "LocalController", "LocalGrid",
           "MclParameters", "MonteCarloLocalisation", "MotionSearchPlanner",
           "NavigateToPose", "NavigationFeedback", "NavigationGoal",
           "NavigationResult", "Navigator", "OdometryPose",
           "StopReason", "TopologicalMap", "astar"]
