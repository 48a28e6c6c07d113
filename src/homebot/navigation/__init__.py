"""Navigation for the simulator: occupancy grid, A*, and the topological map."""

from homebot.navigation.astar import astar
from homebot.navigation.grid import OccupancyGrid
from homebot.navigation.likelihood import LikelihoodField
from homebot.navigation.localisation import MclParameters, MonteCarloLocalisation
from homebot.navigation.navigator import NavigationPlan, Navigator
from homebot.navigation.topology import Route, TopologicalMap

__all__ = ["LikelihoodField", "MclParameters", "MonteCarloLocalisation", "NavigationPlan",
           "Navigator", "OccupancyGrid", "Route", "TopologicalMap", "astar"]
