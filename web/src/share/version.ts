// The site's version (package.json): links carry it, and releases are named by it.
import { version } from '../../../package.json';

export const SITE_VERSION: string = version;
