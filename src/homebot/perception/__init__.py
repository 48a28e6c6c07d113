"""Perception: what the robot's sensors see, and the algorithms that read it.

Objects on tables (catalogue-rendered RGB-D, RANSAC support plane, Euclidean
clustering, recognition), people (legs, tracking), faces, gestures and
Bluetooth lateration. This layer sees the world only through Body-port types
(``RgbdFrame``, ``LaserScan``) and the world's catalogue; it never imports
``homebot.sim``.
"""
