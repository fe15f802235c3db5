"""The Meshcat viewer: a motion drawn as one looping Meshcat animation, live or as a page.

``colours`` (the joint colour scale), ``keyframes`` (the motion resampled at keyframe times and
its keyframe tracks), ``scene`` (robot, ground, force arrows, joint markers), ``page`` (the
self-contained HTML page that plays offline).
"""
