"""Headless MuJoCo Baxter simulation: model, IK, scripted skills, task execution."""
