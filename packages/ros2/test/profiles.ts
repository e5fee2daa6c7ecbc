/** The shipped robot profiles, read as the bridge reads them. */
import { readRobotFolder } from '@armtwin/motion/robot-folder';

export const armtwin5 = () => readRobotFolder('armtwin5');
export const track6 = () => readRobotFolder('track6');
