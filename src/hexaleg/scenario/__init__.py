"""The run: a robot, its actuators and its gait (generated or a recorded log), and what every
command says about it (its warnings, the log's quality)."""
