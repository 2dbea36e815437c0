"""Declarations of Substance's Dirt 1-6 and Grunge Map 001-015 (see functional/noise_grunge.py):
rows of the shared noise recipe table, declared by the same helper as the other noises."""
from ..functional.noise_grunge import GRUNGE_RECIPES
from .noise_generators import register_recipes

register_recipes(GRUNGE_RECIPES)
