"""omni: the Kit modules Isaac Sim's behavior scripts use, over sdgbehave."""
