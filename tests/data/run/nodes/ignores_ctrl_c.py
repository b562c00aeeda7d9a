import time


def main():
    while True:  # no rclpy.ok(), no way out but Ctrl-C
        try:
            time.sleep(1.0)
        except KeyboardInterrupt:
            print('ignoring Ctrl-C')
