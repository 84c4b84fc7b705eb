"""pxr over sdgbehave's stage: the USD modules Isaac Sim's behavior scripts use."""
