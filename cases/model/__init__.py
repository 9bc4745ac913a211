"""Building the model of a scene: gas, cavities, exchanges, bodies, wrapped volumes, blocked areas."""
