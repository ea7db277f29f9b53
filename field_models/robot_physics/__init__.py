"""The mini-robot field model: pymunk differential-drive robots, ball, walls and goals."""
