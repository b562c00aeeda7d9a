import time


def main():
    while True:  # no rclpy.ok(), no way out but Ctrl-C
        time.sleep(1.0)
