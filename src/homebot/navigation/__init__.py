"""Navigation: occupancy grid, stage-1 A*, topological map, localisation, local controllers."""

from homebot.navigation.astar import astar
from homebot.navigation.dwa import DynamicWindowPlanner
from homebot.navigation.grid import OccupancyGrid
from homebot.navigation.likelihood import LikelihoodField
from homebot.navigation.local_planner import MotionSearchPlanner
from homebot.navigation.localisation import MclParameters, MonteCarloLocalisation
from homebot.navigation.localmap import LocalController, LocalGrid, LocalPlannerError
from homebot.navigation.navigate import (
    NavigateToPose,
    NavigationFeedback,
    NavigationGoal,
    NavigationResult,
    OdometryPose,
    StopReason,
)
from homebot.navigation.navigator import NavigationPlan, Navigator
from homebot.navigation.topology import Route, TopologicalMap

__all__ = ["DynamicWindowPlanner", "LikelihoodField", "LocalController", "LocalGrid",
           "LocalPlannerError", "MclParameters", "MonteCarloLocalisation", "MotionSearchPlanner",
           "NavigateToPose", "NavigationFeedback", "NavigationGoal",
           "NavigationPlan", "NavigationResult", "Navigator", "OccupancyGrid", "OdometryPose",
           "Route", "StopReason", "TopologicalMap", "astar"]
