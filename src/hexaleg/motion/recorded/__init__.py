"""Recorded motions: a robot's own log read, resampled, smoothed, its cycle found, its stance and
base reconstructed, into a :class:`~hexaleg.motion.trajectory.Motion` (:func:`load.load_motion`)."""
