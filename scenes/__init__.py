"""Example scenes, installed as package data (``corliss.scenes``)."""
