"""Manipulation: inverse kinematics, grasp planning, RRT-Connect arm motion, picking,
placing and dropping, over the Body port's arm, gripper and wrist sensor."""
