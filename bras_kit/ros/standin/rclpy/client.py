"""rclpy.client, simulated: the client of rclpy.service."""

from .service import Client  # noqa: F401

