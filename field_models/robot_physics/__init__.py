"""The mini-robot system of the paper's §2: pymunk world, overhead camera, host, link, firmware.

The registry builds it through :mod:`~field_models.robot_physics.model`; its arena is
:class:`~field_models.robot_physics.arena.RobotArena`.
"""
