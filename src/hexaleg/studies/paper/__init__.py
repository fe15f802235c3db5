"""The paper's single joint: model, closed forms, readings of its numbers, figures."""
