"""Studies of one joint class at a time: stiffness curves, the older dead-zone spring search
(grid then Nelder-Mead), where springs pay, and the gait study."""
