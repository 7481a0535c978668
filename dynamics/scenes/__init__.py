"""Scenes: TOML files that say what to simulate, read into validated dataclasses."""
